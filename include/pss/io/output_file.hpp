// Atomic output: everything is written to a temporary file beside the destination and
// renamed onto it by commit(), so a crash or an error never leaves a half-written file
// under the final name (rename within one directory is atomic on POSIX).
#pragma once

#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

namespace pss {

class OutputFile {
 public:
  // Creates the temporary; throws file_error(destination, "cannot write: ...").
  explicit OutputFile(std::filesystem::path destination);
  // Removes the temporary unless commit() succeeded.
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  std::ostream& stream() { return out_; }  // binary mode
  // Flushes, checks every write succeeded, and renames onto the destination.
  void commit();

 private:
  std::filesystem::path destination_;
  std::filesystem::path temporary_;
  std::ofstream out_;
  bool committed_ = false;
};

void write_text_file(const std::filesystem::path& path, std::string_view text);

// The whole file in memory: the readers parse from one buffer, which is much faster than
// stream extraction. Throws file_error(path, "cannot open: ...") / "cannot read: ...".
std::string read_file(const std::filesystem::path& path);

}  // namespace pss
