// LZF decompression (Marc Lehmann's liblzf format), for PCD's binary_compressed data. Written
// here rather than linked: it is a few lines, not worth a dependency.
#pragma once

#include <span>
#include <string_view>

namespace pss::io {

// Decompresses `in` into exactly out.size() bytes. Returns the problem of a malformed stream
// (a run or reference past either end, a reference before the start, the wrong length), or an
// empty view on success. Every bound is checked, whatever the input.
std::string_view lzf_decompress(std::string_view in, std::span<char> out);

}  // namespace pss::io
