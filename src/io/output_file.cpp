#include "pss/io/output_file.hpp"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <system_error>

#include "pss/core/error.hpp"

namespace pss {
namespace {

// A failed stream does not always set errno; EIO stands in for "something went wrong".
std::string system_message() { return std::strerror(errno ? errno : EIO); }

Error write_error(const std::filesystem::path& destination, const std::string& why) {
  return file_error(destination, "cannot write: " + why);
}

// Unique per process (pid) and per object (counter), so concurrent writers of the same
// destination, in this process or another, never share a temporary.
std::filesystem::path temporary_beside(const std::filesystem::path& destination) {
  static std::atomic<unsigned> counter{0};
  std::string name = destination.filename().string();
  name += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  return destination.parent_path() / ("." + name);
}

}  // namespace

OutputFile::OutputFile(std::filesystem::path destination)
    : destination_(std::move(destination)), temporary_(temporary_beside(destination_)) {
  errno = 0;
  out_.open(temporary_, std::ios::binary | std::ios::trunc);
  if (!out_) throw write_error(destination_, system_message());
}

OutputFile::~OutputFile() {
  if (committed_) return;
  out_.close();
  std::error_code ignored;  // nothing useful to do with a failure while unwinding
  std::filesystem::remove(temporary_, ignored);
}

void OutputFile::commit() {
  errno = 0;
  out_.flush();
  if (!out_) throw write_error(destination_, system_message());
  out_.close();  // close(2) itself can report a failed write, e.g. on NFS
  if (!out_) throw write_error(destination_, system_message());
  std::error_code ec;
  std::filesystem::rename(temporary_, destination_, ec);
  if (ec) throw write_error(destination_, ec.message());
  committed_ = true;
}

void write_text_file(const std::filesystem::path& path, std::string_view text) {
  OutputFile file(path);
  file.stream().write(text.data(), static_cast<std::streamsize>(text.size()));
  file.commit();
}

std::string read_file(const std::filesystem::path& path) {
  // A directory opens fine on Linux and then reports a nonsense size: refuse it up front.
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw file_error(path, "cannot open: " + std::string(std::strerror(EISDIR)));
  errno = 0;
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw file_error(path, "cannot open: " + system_message());
  const std::streamoff size = in.tellg();
  std::string data;
  if (size > 0) {
    data.resize(static_cast<std::size_t>(size));
    in.seekg(0);
    in.read(data.data(), size);
    if (in.gcount() != size)
      throw file_error(path, "cannot read: " + system_message());
  }
  return data;
}

}  // namespace pss
