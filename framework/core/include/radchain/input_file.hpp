#pragma once
// Files a command reads (sensor files, spectra, result files, shards): checked before they are opened, so that a
// FIFO does not block for ever, a device does not stream without end (/dev/zero), and a directory or an oversized
// file gets a message of its own instead of a parser's.
#include <cstdint>
#include <fstream>
#include <string>

namespace radchain {

// What each kind of input may weigh: far above any real one, far below what would exhaust memory.
inline constexpr std::uintmax_t max_sensor_file_bytes = 16u << 20;    // a sensor file is a few kB
inline constexpr std::uintmax_t max_table_file_bytes = 64u << 20;     // a spectrum or look-up table: thousands of rows
inline constexpr std::uintmax_t max_results_file_bytes = 256u << 20;  // `radchain run --format json` output

// Opens `path` for reading, or throws InputError located at the file and naming it as `what` ("sensor file"):
// missing or unreadable, not a regular file (a directory, FIFO, device or socket), or larger than max_bytes.
std::ifstream open_input_file(const std::string& path, const std::string& what, std::uintmax_t max_bytes,
                              std::ios::openmode mode = std::ios::in);
// The whole file, with the same checks, and again while reading (a file that grows past max_bytes).
std::string read_input_file(const std::string& path, const std::string& what, std::uintmax_t max_bytes);

// Every file opened through these is remembered (device, inode and status-change time) for the life of the process,
// so that an output that names one of the command's inputs is refused instead of replacing it (AtomicFile). `what` it
// was read as ("sensor file"), or "" when `path` is none of them (a new file that reuses a deleted input's inode is
// not one).
std::string input_file_kind(const std::string& path);

}  // namespace radchain
