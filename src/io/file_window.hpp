// A file read front to back through a window of its bytes (issue 28): a reader holds what it
// decodes next, never the whole file, so that reading a cloud costs its points' memory and
// not its file's as well, and a cloud larger than memory can be read in parts. Internal to
// src/io.
#pragma once

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>

namespace pss::io {

// The system's message for errno: a failed stream does not always set it, and EIO stands in
// for "something went wrong". (FileWindow and output_file.cpp.)
std::string system_message();

// Throws file_error(path, "cannot open: ...") for a directory, a FIFO or a device: a
// directory opens fine on Linux and then reports a nonsense size, a FIFO blocks the open
// until a writer comes, a device has no size. What does not exist is left to the open,
// which says so. (read_file and FileWindow.)
void refuse_irregular_file(const std::filesystem::path& path);

class FileWindow {
 public:
  // Opens `path` (a regular file; directories, FIFOs and devices are refused as read_file
  // refuses them) with `window` bytes of buffer, which grows when one read asks for more.
  explicit FileWindow(const std::filesystem::path& path, std::size_t window = default_window());
  ~FileWindow();
  FileWindow(const FileWindow&) = delete;
  FileWindow& operator=(const FileWindow&) = delete;

  std::uint64_t size() const { return size_; }          // the file's size when opened
  std::uint64_t offset() const { return consumed_; }    // bytes consumed so far
  std::uint64_t remaining() const { return size_ > consumed_ ? size_ - consumed_ : 0; }

  // The bytes read but not yet consumed; valid until the next fill.
  std::string_view view() const { return {buffer_.data() + begin_, end_ - begin_}; }
  // Makes view() hold at least `bytes` bytes; false when the file ends first (a file that
  // shrank while it was read ends where its bytes do).
  bool fill(std::size_t bytes);
  void consume(std::size_t bytes) {
    begin_ += bytes;
    consumed_ += bytes;
  }
  // Consumes `bytes` more, through the window a part at a time; false when the file ends
  // first.
  bool skip(std::uint64_t bytes);

  // The default window, 1 MiB; tests shrink it (set_default_window) so that every refill
  // path runs on small files.
  static std::size_t default_window();
  static void set_default_window(std::size_t bytes);

 private:
  std::filesystem::path path_;
  std::FILE* file_ = nullptr;
  std::uint64_t size_ = 0, consumed_ = 0;
  std::string buffer_;
  std::size_t begin_ = 0, end_ = 0;  // view() = buffer_[begin_, end_)
  bool at_end_ = false;
};

}  // namespace pss::io
