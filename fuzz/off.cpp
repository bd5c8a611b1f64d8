// OFF: the input is the file (read_off).
#include "fuzz_input.hpp"
#include "pss/io/off.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace pss::fuzz;
  fresh_folder();
  const auto path = write_file("input.off", as_text(data, size));
  expect_value_or_error([&] { check_cloud(pss::read_off(path)); });
  return 0;
}
