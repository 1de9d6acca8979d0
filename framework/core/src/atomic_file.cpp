#include "radchain/atomic_file.hpp"

#include "radchain/error.hpp"
#include "radchain/input_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <streambuf>

namespace radchain {
namespace {

// The temporaries not yet committed, as C strings a signal handler can unlink (no allocation, no lock).
constexpr int max_pending = 64;
std::atomic<char*> pending[max_pending];
std::atomic<unsigned> temporary_counter{0};

int register_pending(const std::string& path) {
  char* copy = ::strdup(path.c_str());
  if (!copy) return -1;
  for (int i = 0; i < max_pending; ++i) {
    char* expected = nullptr;
    if (pending[i].compare_exchange_strong(expected, copy)) return i;
  }
  std::free(copy);
  return -1;
}

void unregister_pending(int slot) {
  if (slot < 0) return;
  std::free(pending[slot].exchange(nullptr));
}

std::string reason(int error) { return std::strerror(error); }

}  // namespace

// A streambuf over the file descriptor, so a failed write keeps its errno (ENOSPC, EFBIG) for the message.
struct AtomicFile::Buffer : std::streambuf {
  int fd;
  int error = 0;
  char data[1 << 16];
  explicit Buffer(int f) : fd(f) { setp(data, data + sizeof data); }
  bool drain() {
    const char* p = pbase();
    while (p < pptr() && error == 0) {
      const ssize_t n = ::write(fd, p, static_cast<std::size_t>(pptr() - p));
      if (n < 0) {
        if (errno != EINTR) error = errno;
      } else {
        p += n;
      }
    }
    setp(data, data + sizeof data);
    return error == 0;
  }
  int_type overflow(int_type c) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  int sync() override { return drain() ? 0 : -1; }
};

AtomicFile::AtomicFile(std::string path, std::string what) : path_(std::move(path)), what_(std::move(what)) {
  namespace fs = std::filesystem;
  struct stat st {};
  if (::stat(path_.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
    if (S_ISDIR(st.st_mode)) throw InputError(SourceLocation{what_, 0, 0}, "", path_, "is a folder, not a file");
    in_place_ = true;  // a device or a FIFO: written in place
    temporary_ = path_;
    fd_ = ::open(path_.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd_ < 0) throw InputError(SourceLocation{what_, 0, 0}, "", path_, "cannot be written: " + reason(errno));
    return;
  }
  auto refuse = [&](const std::string& problem) { return InputError(SourceLocation{what_, 0, 0}, "", path_, problem); };
  refuse_an_input();
  // Replacing a file keeps what the user made of it: a link stays a link (the file it names is replaced), and the
  // replacement gets the old file's mode and owner. Hard links cannot be kept by a rename: refused.
  target_ = path_;
  struct stat existing {};
  const bool replacing = ::lstat(path_.c_str(), &existing) == 0;
  if (replacing && S_ISLNK(existing.st_mode)) {
    std::error_code ec;
    target_ = fs::canonical(path_, ec).string();
    if (ec) throw refuse("is a link to a missing file (" + reason(ec.value()) + "): remove the link or write elsewhere");
    if (::stat(target_.c_str(), &existing) != 0) throw refuse("cannot be examined: " + reason(errno));
  }
  if (replacing && existing.st_nlink > 1)
    throw refuse(std::to_string(existing.st_nlink) + " names share this file (hard links); replacing it would split them: "
                 "remove it first or write elsewhere");
  const fs::path target(target_);
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  const std::string name = target.filename().string();
  if (name.empty()) throw refuse("names a folder, not a file");
  // Hidden, in the same folder (rename stays on one file system), the target's name last so its extension is kept.
  for (int attempt = 0; attempt < 100 && fd_ < 0; ++attempt) {
    temporary_ = (folder / (".radchain-" + std::to_string(::getpid()) + "-" + std::to_string(temporary_counter++) +
                            "-" + name))
                     .string();
    fd_ = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd_ < 0 && errno != EEXIST) break;
  }
  if (fd_ < 0)
    throw InputError(SourceLocation{what_, 0, 0}, "", path_,
                     "cannot be written (" + reason(errno) + "; missing folder or no permission?)");
  slot_ = register_pending(temporary_);
  if (!replacing) return;
  struct stat created {};
  const bool owner_kept = ::fstat(fd_, &created) == 0 &&
                          ((created.st_uid == existing.st_uid && created.st_gid == existing.st_gid) ||
                           ::fchown(fd_, existing.st_uid, existing.st_gid) == 0);
  if (!owner_kept || ::fchmod(fd_, existing.st_mode & 07777) != 0) {
    const int error = errno;
    discard();
    throw refuse("belongs to another user or group (" + reason(error) +
                 "): replacing it would change its owner or mode; write elsewhere");
  }
}

// An output that is one of the command's own inputs (a sensor file, a spectrum it reads, a shard it merges).
void AtomicFile::refuse_an_input() const {
  const std::string kind = input_file_kind(path_);
  if (!kind.empty())
    throw InputError(SourceLocation{what_, 0, 0}, "", path_,
                     "is one of this command's inputs (a " + kind + " it reads): writing it would replace the input; "
                     "write elsewhere");
}

AtomicFile::~AtomicFile() { discard(); }

void AtomicFile::discard() noexcept {
  stream_.reset();
  buffer_.reset();
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (!committed_ && !in_place_ && !temporary_.empty()) ::unlink(temporary_.c_str());
  unregister_pending(slot_);
  slot_ = -1;
}

std::ostream& AtomicFile::stream() {
  if (!stream_) {
    buffer_ = std::make_unique<Buffer>(fd_);
    stream_ = std::make_unique<std::ostream>(buffer_.get());
  }
  return *stream_;
}

void AtomicFile::commit() {
  if (committed_) return;
  auto fail = [&](int error) {
    const std::string message = "cannot write " + path_ + ": " + reason(error) + (in_place_ ? "" : " (nothing written)");
    discard();
    throw WriteError(message);
  };
  if (stream_) {
    stream_->flush();
    if (buffer_->error) fail(buffer_->error);
    if (!*stream_) fail(EIO);
  }
  if (!in_place_) {
    try {
      refuse_an_input();  // (an input read after the output was opened)
    } catch (...) {
      discard();
      throw;
    }
  }
  if (!in_place_ && ::fsync(fd_) != 0) fail(errno);
  const int closed = ::close(fd_);
  fd_ = -1;
  if (closed != 0 && errno != EINTR) fail(errno);
  if (!in_place_ && ::rename(temporary_.c_str(), target_.c_str()) != 0) fail(errno);
  committed_ = true;
  unregister_pending(slot_);
  slot_ = -1;
}

void AtomicFile::remove_pending() noexcept {
  for (auto& slot : pending)
    if (const char* path = slot.load()) ::unlink(path);
}

void check_standard_output() {
  std::cout.flush();
  errno = 0;
  const bool failed = !std::cout || std::fflush(stdout) != 0 || std::ferror(stdout);
  if (failed) {
    const int error = errno;  // 0 when the failed write was an earlier one (its errno is gone)
    std::clearerr(stdout);
    throw WriteError("cannot write standard output: " + (error ? reason(error) : std::string("a write failed (disk full?)")));
  }
}

}  // namespace radchain
