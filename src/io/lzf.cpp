#include "lzf.hpp"

#include <cstring>

namespace pss::io {

// Each chunk starts with a control byte c. c < 32: c + 1 literal bytes follow. Otherwise a
// back-reference: length c >> 5 (when it is 7, plus the next byte), plus 2; distance
// (c & 31) << 8 | the next byte, plus 1, back from the end of the output so far. A reference
// may overlap the bytes it produces (distance < length repeats a pattern).
std::string_view lzf_decompress(std::string_view in, std::span<char> out) {
  std::size_t ip = 0, op = 0;
  const auto next = [&] { return static_cast<unsigned char>(in[ip++]); };
  while (ip < in.size()) {
    const unsigned control = next();
    if (control < 32) {
      const std::size_t run = control + 1;
      if (run > in.size() - ip) return "a literal run passes the end of the compressed data";
      if (run > out.size() - op) return "the data decompresses to more bytes than the header says";
      std::memcpy(out.data() + op, in.data() + ip, run);
      ip += run;
      op += run;
      continue;
    }
    std::size_t length = control >> 5;
    if (length == 7) {
      if (ip == in.size()) return "a back-reference passes the end of the compressed data";
      length += next();
    }
    if (ip == in.size()) return "a back-reference passes the end of the compressed data";
    const std::size_t distance = ((control & 31u) << 8 | next()) + 1;
    length += 2;
    if (distance > op) return "a back-reference points before the start of the data";
    if (length > out.size() - op) return "the data decompresses to more bytes than the header says";
    for (const std::size_t end = op + length; op < end; ++op) out[op] = out[op - distance];
  }
  if (op != out.size()) return "the data decompresses to fewer bytes than the header says";
  return {};
}

}  // namespace pss::io
