#pragma once
// A file written whole or not at all. Every file radchain writes (tables, shards, MTF CSV, plots, images) goes
// through AtomicFile: the bytes go to a temporary name in the same folder and are renamed over the target by
// commit(), after a flush, an error check and fsync. Destroyed without commit() (an exception, a failed check that
// writes nothing), the temporary is removed and a file already at the target is untouched. A target that exists and
// is not a regular file (/dev/full, /dev/stdout, a FIFO) is written in place: there is nothing to rename, but a
// write error is still reported.
// A file replaced keeps its mode and owner (or is refused), a symbolic link keeps naming the replaced file, a file
// with hard links is refused, and so is a target that is one of the command's inputs (radchain/input_file.hpp).
#include <memory>
#include <ostream>
#include <stdexcept>
#include <string>

namespace radchain {

// A write that failed (disk full, file size limit, I/O error): the message names the file and the system's reason.
class WriteError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class AtomicFile {
 public:
  // Creates the temporary file; an InputError at "--out"-like `what` when the folder is missing or not writable.
  explicit AtomicFile(std::string path, std::string what = "--out");
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  const std::string& path() const { return path_; }
  // The name to write to for a library that opens files by name (OpenImageIO, gnuplot): same folder, same
  // extension as path() (a writer picks its format by extension). Do not use together with stream().
  const std::string& temporary_path() const { return temporary_; }
  std::ostream& stream();
  // Flushes, checks, syncs and renames the temporary over path(); throws WriteError. Idempotent.
  void commit();

  // Removes every temporary file not yet committed. Async-signal-safe: for a SIGINT/SIGTERM handler.
  static void remove_pending() noexcept;

 private:
  struct Buffer;
  std::string path_, what_, temporary_;
  std::string target_;  // the file renamed over: path_, or the file a link at path_ names
  int fd_ = -1;
  bool in_place_ = false, committed_ = false;
  int slot_ = -1;
  std::unique_ptr<Buffer> buffer_;
  std::unique_ptr<std::ostream> stream_;
  void discard() noexcept;
  void refuse_an_input() const;
};

// Flushes standard output and throws WriteError if any write to it failed (`radchain run ... >/dev/full`).
void check_standard_output();

}  // namespace radchain
