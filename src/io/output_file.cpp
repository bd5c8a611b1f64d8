#include "pss/io/output_file.hpp"

#include <fcntl.h>
#include <sys/resource.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <mutex>
#include <system_error>

#include "pss/core/error.hpp"
#include "file_window.hpp"

namespace pss {
namespace {

namespace fs = std::filesystem;
using io::system_message;

Error write_error(const fs::path& destination, const std::string& why) {
  return file_error(destination, "cannot write: " + why);
}

// Why a write to `file` failed, after the fact: the process's file-size limit reached, or
// its file system full; else an I/O error.
std::string lost_write_reason(const fs::path& file) {
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(file, ec);
  struct rlimit limit {};
  if (!ec && ::getrlimit(RLIMIT_FSIZE, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY && size >= limit.rlim_cur)
    return std::strerror(EFBIG);
  const fs::space_info space = fs::space(file.parent_path().empty() ? fs::path(".") : file.parent_path(), ec);
  if (!ec && space.available == 0) return std::strerror(ENOSPC);
  return std::strerror(EIO);
}

// Unique per process (pid) and per object (counter), so concurrent writers of the same
// destination, in this process or another, never share a temporary.
fs::path temporary_beside(const fs::path& destination) {
  static std::atomic<unsigned> counter{0};
  std::string name = destination.filename().string();
  name += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  return destination.parent_path() / ("." + name);
}

// The temporaries that exist now, for the handler of SIGINT, SIGTERM and SIGHUP, which
// unlinks them and dies of the signal as it would have without the handler. Only
// async-signal-safe operations touch the table in the handler: lock-free atomics, unlink(2),
// signal(2), raise(3). A slot is free (0), being filled (1) or holds a path (2).
namespace temporaries {

constexpr int kSlots = 64;
constexpr std::size_t kPathSize = 4096;
struct Slot {
  std::atomic<int> state{0};
  char path[kPathSize];
};
Slot slots[kSlots];
static_assert(std::atomic<int>::is_always_lock_free);
constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};

extern "C" void remove_and_reraise(int signal_number) {
  const int saved_errno = errno;
  for (Slot& slot : slots)
    if (slot.state.load(std::memory_order_acquire) == 2) ::unlink(slot.path);
  errno = saved_errno;
  // SA_RESETHAND restored the default action; the signal is blocked until we return, then
  // delivered again and ends the process with the status a parent expects.
  std::raise(signal_number);
}

void install_handler() {
  static std::once_flag once;
  std::call_once(once, [] {
    struct sigaction action {};
    action.sa_handler = remove_and_reraise;
    action.sa_flags = SA_RESETHAND;
    sigemptyset(&action.sa_mask);
    for (int s : kSignals) sigaddset(&action.sa_mask, s);
    for (int s : kSignals) {
      struct sigaction old {};
      // Leave alone a signal that is ignored (nohup) or that the program handles itself.
      if (::sigaction(s, nullptr, &old) != 0 || old.sa_handler != SIG_DFL || (old.sa_flags & SA_SIGINFO)) continue;
      ::sigaction(s, &action, nullptr);
    }
  });
}

// Call before the file is created. A path too long or a full table is not remembered: the
// file is still removed on errors, only not on a signal.
void add(const fs::path& path) {
  install_handler();
  std::error_code ec;
  const std::string text = fs::absolute(path, ec).string();  // the handler needs no cwd
  if (ec || text.size() >= kPathSize) return;
  for (Slot& slot : slots) {
    int expected = 0;
    if (!slot.state.compare_exchange_strong(expected, 1, std::memory_order_acq_rel)) continue;
    std::memcpy(slot.path, text.c_str(), text.size() + 1);
    slot.state.store(2, std::memory_order_release);
    return;
  }
}

// Call once the file is renamed or removed.
void forget(const fs::path& path) {
  std::error_code ec;
  const std::string text = fs::absolute(path, ec).string();
  for (Slot& slot : slots)
    if (slot.state.load(std::memory_order_acquire) == 2 && text == slot.path) {
      slot.state.store(0, std::memory_order_release);
      return;
    }
}

}  // namespace temporaries

void remove_temporary(const fs::path& temporary) {
  std::error_code ignored;  // nothing useful to do with a failure while unwinding
  fs::remove(temporary, ignored);
  temporaries::forget(temporary);
}

fs::path key_of(const fs::path& path) {
  std::error_code ec;
  const fs::path absolute = fs::absolute(path, ec);
  return (ec ? path : absolute).lexically_normal();
}

// The same file: the same path once made absolute and symlinks and ".." are resolved (a
// relative path that does not exist yet is otherwise left as it is: "o.png" and "./o.png"
// differed), or (both existing) the same inode, which also catches hard links.
bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code ec1, ec2;
  const fs::path ca = fs::weakly_canonical(key_of(a), ec1), cb = fs::weakly_canonical(key_of(b), ec2);
  if (!ec1 && !ec2 && ca == cb) return true;
  std::error_code ec;
  return fs::equivalent(a, b, ec) && !ec;
}

// Refuse, rather than write into or rename over, anything at the destination that exists
// and is not a regular file. Renaming would replace a FIFO, a device node (as root,
// -o /dev/full replaced the system's node) or a symlink (the link, not its target) by a
// regular file; writing into them directly would give up the all-or-nothing guarantee,
// block on a FIFO without a reader, write through a symlink planted in a shared directory,
// or write to a disk as root. Leaving out the option is the way to write no file.
void check_output(const fs::path& output, const std::vector<fs::path>& inputs,
                  const std::vector<fs::path>& earlier_outputs) {
  std::error_code ec;
  const fs::file_status status = fs::symlink_status(output, ec);
  if (!ec && fs::exists(status)) {
    if (fs::is_symlink(status)) throw write_error(output, "is a symbolic link (refusing to replace it)");
    if (fs::is_directory(status)) throw write_error(output, std::strerror(EISDIR));
    if (!fs::is_regular_file(status)) throw write_error(output, "not a regular file (refusing to replace it)");
  }
  const fs::path parent = key_of(output).parent_path();
  if (!fs::is_directory(parent, ec)) throw write_error(output, "no directory " + parent.string());
  if (::access(parent.c_str(), W_OK | X_OK) != 0)
    throw write_error(output, "directory " + parent.string() + ": " + system_message());
  for (const fs::path& input : inputs)
    if (!input.empty() && same_file(output, input)) throw write_error(output, "it is the input");
  for (const fs::path& other : earlier_outputs)
    if (same_file(output, other)) throw write_error(output, "named twice as an output");
}

thread_local OutputSet* active_set = nullptr;

}  // namespace

OutputFile::OutputFile(fs::path destination) : destination_(std::move(destination)) {
  if (OutputSet* set = OutputSet::active())
    if (const OutputSet::Entry* entry = set->find(destination_)) {
      temporary_ = entry->temporary;
      reserved_ = true;
    }
  if (!reserved_) {
    temporary_ = temporary_beside(destination_);
    temporaries::add(temporary_);
  }
  errno = 0;
  out_.open(temporary_, std::ios::binary | std::ios::trunc);
  if (!out_) {
    const std::string why = system_message();
    if (!reserved_) temporaries::forget(temporary_);
    throw write_error(destination_, why);
  }
}

OutputFile::~OutputFile() {
  if (committed_) return;
  out_.close();
  if (!reserved_) remove_temporary(temporary_);  // a reserved one stays with its OutputSet
}

void OutputFile::commit() {
  // A write that failed before left the stream bad, and errno may be gone since: the usual
  // causes are read off the file system instead.
  if (!out_) throw write_error(destination_, lost_write_reason(temporary_));
  errno = 0;
  out_.flush();
  if (!out_) throw write_error(destination_, system_message());
  out_.close();  // close(2) itself can report a failed write, e.g. on NFS
  if (!out_) throw write_error(destination_, system_message());
  if (OutputSet* set = OutputSet::active()) {
    set->adopt(destination_, temporary_);
    committed_ = true;
    return;
  }
  std::error_code ec;
  fs::rename(temporary_, destination_, ec);
  if (ec) throw write_error(destination_, ec.message());
  temporaries::forget(temporary_);
  committed_ = true;
}

OutputSet::OutputSet(const std::vector<fs::path>& inputs, const std::vector<fs::path>& outputs) {
  std::vector<fs::path> checked;
  for (const fs::path& output : outputs) {
    if (output.empty()) continue;
    check_output(output, inputs, checked);
    checked.push_back(output);
  }
  try {
    for (const fs::path& output : checked) {
      Entry entry{output, temporary_beside(output)};
      temporaries::add(entry.temporary);
      errno = 0;
      const int fd = ::open(entry.temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
      if (fd < 0) {
        const std::string why = system_message();
        temporaries::forget(entry.temporary);
        throw write_error(output, why);
      }
      ::close(fd);
      entries_.push_back(std::move(entry));
    }
  } catch (...) {
    for (const Entry& entry : entries_) remove_temporary(entry.temporary);
    throw;
  }
  previous_ = active_set;
  active_set = this;
}

OutputSet::~OutputSet() {
  if (active_set == this) active_set = previous_;
  if (committed_) return;
  for (const Entry& entry : entries_) remove_temporary(entry.temporary);
}

OutputSet* OutputSet::active() { return active_set; }

OutputSet::Entry* OutputSet::find(const fs::path& destination) {
  const fs::path key = key_of(destination);
  for (Entry& entry : entries_)
    if (key_of(entry.destination) == key) return &entry;
  return nullptr;
}

void OutputSet::adopt(const fs::path& destination, const fs::path& temporary) {
  if (Entry* entry = find(destination)) {
    if (entry->temporary != temporary) {  // a second, unreserved file for the same output
      remove_temporary(entry->temporary);
      entry->temporary = temporary;
    }
    entry->written = true;
    return;
  }
  entries_.push_back(Entry{destination, temporary, true});
}

void OutputSet::commit() {
  for (const Entry& entry : entries_)
    if (!entry.written) throw write_error(entry.destination, "nothing was written (internal error)");
  for (const Entry& entry : entries_) {
    std::error_code ec;
    fs::rename(entry.temporary, entry.destination, ec);
    if (ec) throw write_error(entry.destination, ec.message());
    temporaries::forget(entry.temporary);
  }
  committed_ = true;
  if (active_set == this) active_set = previous_;
}

void write_text_file(const std::filesystem::path& path, std::string_view text) {
  OutputFile file(path);
  file.stream().write(text.data(), static_cast<std::streamsize>(text.size()));
  file.commit();
}

std::string read_file(const std::filesystem::path& path) {
  io::refuse_irregular_file(path);  // a header's detached data file may name a FIFO
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

ScratchFile::ScratchFile(const std::filesystem::path& folder)
    : path_(temporary_beside(folder / "pss-scratch")) {
  temporaries::add(path_);
  errno = 0;
  descriptor_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (descriptor_ < 0) {
    const std::string why = system_message();
    temporaries::forget(path_);
    throw write_error(path_, why);
  }
}

ScratchFile::~ScratchFile() {
  ::close(descriptor_);
  remove_temporary(path_);
}

void ScratchFile::write_at(std::uint64_t offset, const void* bytes, std::size_t size) {
  const char* from = static_cast<const char*>(bytes);
  while (size > 0) {
    errno = 0;
    const ssize_t done = ::pwrite(descriptor_, from, size, off_t(offset));
    if (done < 0 && errno == EINTR) continue;
    if (done <= 0) throw write_error(path_, system_message());
    from += done;
    offset += std::uint64_t(done);
    size -= std::size_t(done);
  }
}

void ScratchFile::read_at(std::uint64_t offset, void* bytes, std::size_t size) const {
  char* to = static_cast<char*>(bytes);
  while (size > 0) {
    errno = 0;
    const ssize_t done = ::pread(descriptor_, to, size, off_t(offset));
    if (done < 0 && errno == EINTR) continue;
    if (done <= 0) throw file_error(path_, "cannot read: " + (done == 0 ? std::string("it ended early") : system_message()));
    to += done;
    offset += std::uint64_t(done);
    size -= std::size_t(done);
  }
}

}  // namespace pss
