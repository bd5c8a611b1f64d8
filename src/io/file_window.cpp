#include "file_window.hpp"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>

#include "pss/core/error.hpp"

namespace pss::io {

namespace {

std::atomic<std::size_t> window_bytes{std::size_t(1) << 20};

}  // namespace

std::string system_message() { return std::strerror(errno ? errno : EIO); }

std::size_t FileWindow::default_window() { return window_bytes; }
void FileWindow::set_default_window(std::size_t bytes) { window_bytes = std::max<std::size_t>(bytes, 1); }

void refuse_irregular_file(const std::filesystem::path& path) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (std::filesystem::is_directory(status)) throw file_error(path, "cannot open: " + std::string(std::strerror(EISDIR)));
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
    throw file_error(path, "cannot open: not a regular file");
}

FileWindow::FileWindow(const std::filesystem::path& path, std::size_t window) : path_(path) {
  refuse_irregular_file(path);
  std::error_code ec;
  errno = 0;
  file_ = std::fopen(path.c_str(), "rb");
  if (!file_) throw file_error(path, "cannot open: " + system_message());
  const auto size = std::filesystem::file_size(path, ec);
  size_ = ec ? 0 : size;
  buffer_.resize(std::max<std::size_t>(window, 1));
}

FileWindow::~FileWindow() {
  if (file_) std::fclose(file_);
}

bool FileWindow::fill(std::size_t bytes) {
  // A count the file cannot hold (a corrupt list length) never sizes the buffer.
  if (bytes > end_ - begin_ && bytes > remaining()) return false;
  while (end_ - begin_ < bytes) {
    if (at_end_) return false;
    // The unread bytes move to the front; the buffer grows only for a read longer than it.
    if (begin_ > 0) {
      std::memmove(buffer_.data(), buffer_.data() + begin_, end_ - begin_);
      end_ -= begin_;
      begin_ = 0;
    }
    if (buffer_.size() < bytes) buffer_.resize(bytes);
    errno = 0;
    const std::size_t got = std::fread(buffer_.data() + end_, 1, buffer_.size() - end_, file_);
    if (got == 0) {
      if (std::ferror(file_)) throw file_error(path_, "cannot read: " + system_message());
      at_end_ = true;
    }
    end_ += got;
  }
  return true;
}

bool FileWindow::skip(std::uint64_t bytes) {
  while (bytes > 0) {
    if (begin_ == end_ && !fill(std::size_t(std::min<std::uint64_t>(bytes, buffer_.size())))) return false;
    const std::size_t part = std::size_t(std::min<std::uint64_t>(bytes, end_ - begin_));
    consume(part);
    bytes -= part;
  }
  return true;
}

}  // namespace pss::io
