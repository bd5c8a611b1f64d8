// NRRD (read_nrrd): input.nrrd with attached data, or input.nhdr naming "data file:
// data.raw", raw or gzip (the layout: write_header_and_data).
#include "fuzz_input.hpp"
#include "pss/io/volume_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace pss::fuzz;
  const auto path = write_header_and_data(as_text(data, size), "input.nrrd", "input.nhdr");
  expect_value_or_error([&] { check_volume(pss::read_nrrd(path)); });
  return 0;
}
