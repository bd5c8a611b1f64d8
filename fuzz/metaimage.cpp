// MetaImage (read_metaimage): input.mha with "ElementDataFile = LOCAL", or input.mhd naming
// "ElementDataFile = data.raw", raw or compressed (the layout: write_header_and_data).
#include "fuzz_input.hpp"
#include "pss/io/volume_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace pss::fuzz;
  const auto path = write_header_and_data(as_text(data, size), "input.mha", "input.mhd");
  expect_value_or_error([&] { check_volume(pss::read_metaimage(path)); });
  return 0;
}
