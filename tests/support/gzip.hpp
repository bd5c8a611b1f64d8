// gzip-compressing bytes for tests that write compressed volumes (NRRD, MetaImage, NIfTI)
// or bombs, with zlib as a program other than pss would.
#pragma once

#include <string>

namespace pss::test {

std::string gzip(const std::string& data);

}  // namespace pss::test
