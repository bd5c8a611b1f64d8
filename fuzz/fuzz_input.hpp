// What the fuzz targets share. The readers take paths, so a target writes its input into
// files of a folder private to the process (made on first use under $TMPDIR, emptied for
// each input, removed at exit) and reads them back through pss. A pss::Error is the
// expected end of bad input; anything else is a finding: another exception (reported here,
// then abort), a crash, a sanitizer report, runaway memory or time (libFuzzer's limits).
// What a reader returns must keep its documented promises (check_cloud, check_volume), and
// an error must be one printable line of bounded length (check_message).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <string_view>
#include <typeinfo>

#include "pss/core/error.hpp"
#include "pss/points/cloud.hpp"
#include "pss/volume/volume.hpp"

namespace pss::fuzz {

// The input as bytes of text.
inline std::string_view as_text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

// Empties this process's folder, so that no file of an earlier input is found, and
// returns it.
const std::filesystem::path& fresh_folder();

// Writes `bytes` to the file `name` of the folder; returns its path.
std::filesystem::path write_file(const std::string& name, std::string_view bytes);

// The multi-file targets (a header and its data file, or a header and the data the target
// compresses) take "HEAD" kSeparator "TAIL"; without the separator, all is HEAD and there is
// no TAIL.
inline constexpr std::string_view kSeparator = "\n--pss-fuzz-data--\n";
struct Parts {
  std::string_view head, tail;
  bool has_tail = false;
};
Parts split_parts(std::string_view input);

// The first byte as option bits (0 without one) and the bytes after it.
struct Mode {
  unsigned bits = 0;
  std::string_view rest;
};
Mode take_mode(std::string_view input);

// The files of a format whose header has its data attached or detached (NRRD, MetaImage),
// from an input of: a mode byte, then HEAD kSeparator TAIL. Mode bit 0: detached, HEAD is
// the file `detached_name` and TAIL the file data.raw beside it (no TAIL, no data file),
// which the seeds' headers name; else HEAD then TAIL make the file `attached_name`. Bit 1:
// the target gzips TAIL, so compressed data can still be changed byte by byte. Empties the
// folder first; returns the header's path.
std::filesystem::path write_header_and_data(std::string_view input, const std::string& attached_name,
                                            const std::string& detached_name);

// gzip's format, as other programs write it (tests/support/gzip.cpp).
std::string gzip(std::string_view bytes);

// Aborts with `what` on stderr: libFuzzer and the replay driver report the input.
[[noreturn]] void finding(const std::string& what);

// The promises of the point-cloud readers: at least one point, every coordinate finite,
// normals absent or one per point, each unit length or zero.
void check_cloud(const PointCloud& cloud);
// The promises of the volume readers: positive dims, one finite value per voxel, positive
// finite spacing, finite origin.
void check_volume(const Volume& volume);
// An error message: one line (no control bytes) of at most kMaxMessageBytes.
inline constexpr std::size_t kMaxMessageBytes = 2048;
void check_message(std::string_view message);

// With PSS_FUZZ_VERBOSE set (any value), the replay prints each input's outcome: "ok" or
// the error message. For looking at what a corpus reaches.
void report(std::string_view outcome);

// Runs read(); returns normally for a pss::Error (after check_message), calls finding()
// for any other exception.
template <class Read>
void expect_value_or_error(Read&& read) {
  try {
    read();
    report("ok");
  } catch (const Error& e) {
    check_message(e.what());
    report(e.what());
  } catch (const std::exception& e) {
    finding(std::string("unexpected ") + typeid(e).name() + ": " + e.what());
  }
}

}  // namespace pss::fuzz
