// PCD: the input is the file (read_pcd).
#include "fuzz_input.hpp"
#include "pss/io/pcd.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace pss::fuzz;
  fresh_folder();
  const auto path = write_file("input.pcd", as_text(data, size));
  expect_value_or_error([&] { check_cloud(pss::read_pcd(path)); });
  return 0;
}
