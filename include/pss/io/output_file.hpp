// Atomic output: everything is written to a temporary file beside the destination and
// renamed onto it by commit(), so a crash or an error never leaves a half-written file
// under the final name (rename within one directory is atomic on POSIX).
//
// A command with several outputs (an image, --hits, --stats) makes them all-or-nothing with
// an OutputSet: it checks every destination before any work and reserves its temporary;
// while the set is alive, OutputFile::commit() leaves its file as a temporary in the set,
// and OutputSet::commit() renames them all at the end. Temporaries are removed on SIGINT,
// SIGTERM and SIGHUP as well as on errors.
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

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
  // Flushes, checks every write succeeded, and renames onto the destination; inside an
  // OutputSet it hands the finished temporary to the set instead, which renames it later.
  void commit();

 private:
  std::filesystem::path destination_;
  std::filesystem::path temporary_;
  std::ofstream out_;
  bool committed_ = false;
  bool reserved_ = false;  // the temporary belongs to the active OutputSet
};

// The outputs of one command, committed together. Empty paths are skipped.
class OutputSet {
 public:
  // Checks each output and throws file_error(output, "cannot write: ...") for one that
  // exists and is not a regular file (directory, FIFO, device, socket, symlink), whose
  // directory is missing or not writable, that is one of the inputs, or that is named twice.
  // Then reserves (creates, empty) the temporary of each output, which proves it can be
  // created. Becomes the active set of this thread until destroyed.
  OutputSet(const std::vector<std::filesystem::path>& inputs, const std::vector<std::filesystem::path>& outputs);
  // Removes every temporary not committed.
  ~OutputSet();
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  // Renames every finished temporary onto its destination. Throws file_error for an output
  // that was reserved but never written. POSIX has no atomic rename of several files: a
  // rename that fails after others succeeded (disk pulled out) leaves those in place.
  void commit();

  // The set OutputFile hands its temporaries to, or nullptr.
  static OutputSet* active();

 private:
  friend class OutputFile;
  struct Entry {
    std::filesystem::path destination, temporary;
    bool written = false;
  };
  Entry* find(const std::filesystem::path& destination);
  void adopt(const std::filesystem::path& destination, const std::filesystem::path& temporary);

  std::vector<Entry> entries_;
  OutputSet* previous_ = nullptr;
  bool committed_ = false;
};

void write_text_file(const std::filesystem::path& path, std::string_view text);

// A command's own temporary file (issue 28: a cloud's tiles on disk), named for this process
// in `folder`, read and written at offsets; removed when destroyed, and on SIGINT, SIGTERM
// and SIGHUP as the outputs' temporaries are. Every failure (a folder that cannot take it, a
// full disk) throws file_error naming the file.
class ScratchFile {
 public:
  explicit ScratchFile(const std::filesystem::path& folder);
  ~ScratchFile();
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;

  const std::filesystem::path& path() const { return path_; }
  void write_at(std::uint64_t offset, const void* bytes, std::size_t size);
  void read_at(std::uint64_t offset, void* bytes, std::size_t size) const;

 private:
  std::filesystem::path path_;
  int descriptor_ = -1;
};

// The whole file in memory: the readers parse from one buffer, which is much faster than
// stream extraction. Throws file_error(path, "cannot open: ...") / "cannot read: ..."; a
// directory, FIFO or device is refused before it is opened.
std::string read_file(const std::filesystem::path& path);

}  // namespace pss
