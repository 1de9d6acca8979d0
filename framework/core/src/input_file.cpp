#include "radchain/input_file.hpp"

#include "radchain/error.hpp"

#include <fmt/format.h>

#include <sys/stat.h>

#include <filesystem>
#include <map>
#include <mutex>
#include <system_error>
#include <utility>

namespace radchain {

namespace {

InputError input_error(const std::string& path, const std::string& what, const std::string& problem) {
  return InputError(SourceLocation{path, 0, 0}, what, "", problem);
}

// Every input file read, by device and inode, with its status-change time and what it was read as. The time tells a
// file apart from a later one that reuses a deleted input's inode (a long Python session). Worker threads load
// chains concurrently.
struct InputSeen {
  std::string what;
  timespec changed{};
};
std::mutex inputs_mutex;
std::map<std::pair<dev_t, ino_t>, InputSeen> inputs;

void remember_input(const std::string& path, const std::string& what) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return;
  const std::lock_guard lock(inputs_mutex);
  inputs.insert_or_assign(std::make_pair(st.st_dev, st.st_ino), InputSeen{what, st.st_ctim});
}

std::string size_text(std::uintmax_t bytes) {
  return bytes >= (1u << 20) ? fmt::format("{} MiB", bytes >> 20) : fmt::format("{} kB", bytes >> 10);
}

}  // namespace

std::ifstream open_input_file(const std::string& path, const std::string& what, std::uintmax_t max_bytes,
                              std::ios::openmode mode) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);  // (follows a link: what it names is what is read)
  if (ec || !fs::exists(status)) throw input_error(path, what, "cannot be read (missing file or no permission)");
  if (fs::is_directory(status)) throw input_error(path, what, "is a directory, not a file");
  if (!fs::is_regular_file(status))
    throw input_error(path, what, "is not a regular file (a FIFO, device or socket is not read: it may never end)");
  const std::uintmax_t size = fs::file_size(path, ec);
  if (!ec && size > max_bytes)
    throw input_error(path, what, fmt::format("{} bytes: larger than a {} may be ({})", size, what, size_text(max_bytes)));
  std::ifstream in(path, mode);
  if (!in) throw input_error(path, what, "cannot be read (missing file or no permission)");
  remember_input(path, what);
  return in;
}

std::string input_file_kind(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return {};
  const std::lock_guard lock(inputs_mutex);
  const auto found = inputs.find(std::make_pair(st.st_dev, st.st_ino));
  if (found == inputs.end() || found->second.changed.tv_sec != st.st_ctim.tv_sec ||
      found->second.changed.tv_nsec != st.st_ctim.tv_nsec)
    return {};
  return found->second.what;
}

std::string read_input_file(const std::string& path, const std::string& what, std::uintmax_t max_bytes) {
  std::ifstream in = open_input_file(path, what, max_bytes, std::ios::in | std::ios::binary);
  std::string text;
  char chunk[65536];
  while (in.read(chunk, sizeof chunk) || in.gcount() > 0) {
    text.append(chunk, static_cast<std::size_t>(in.gcount()));
    if (text.size() > max_bytes)
      throw input_error(path, what, fmt::format("grew past {} while being read", size_text(max_bytes)));
  }
  if (in.bad()) throw input_error(path, what, "could not be read to its end (an I/O error)");
  return text;
}

}  // namespace radchain
