// NIfTI-1 (read_nifti). The first byte chooses: bit 0 the name input.nii.gz (else
// input.nii); bit 1: the target gzips the rest (so the fuzzer changes the header and voxels
// of a .nii.gz byte by byte); without it the rest is the file as it is (a gzip stream the
// fuzzer corrupts, or an uncompressed file, under either name).
#include <string>

#include "fuzz_input.hpp"
#include "pss/io/volume_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace pss::fuzz;
  const Mode mode = take_mode(as_text(data, size));
  const std::string bytes = mode.bits & 2 ? gzip(mode.rest) : std::string(mode.rest);
  fresh_folder();
  const auto path = write_file(mode.bits & 1 ? "input.nii.gz" : "input.nii", bytes);
  expect_value_or_error([&] { check_volume(pss::read_nifti(path)); });
  return 0;
}
