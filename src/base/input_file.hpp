#pragma once
/// @file
/// Reading a whole file that a user, another tool or another process hands over (a config,
/// a record, a command list, a robot description, a checkpoint): the one place that refuses
/// what would hang or exhaust memory. A FIFO blocks its reader until a writer comes; a
/// device such as /dev/zero never ends; a huge file fills the memory.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace upkie_rl {

/// Reads the whole of `path` into `bytes` if it is a regular file of at most `max_bytes`;
/// otherwise returns why not ("cannot open: no such file or directory", "is a directory", "not a
/// regular file (a FIFO, a device or a socket)", "N bytes, more than the limit of M bytes", a read
/// error) and leaves `bytes` empty. Never blocks on a FIFO (checked before and after a
/// non-blocking open), and reads at most `max_bytes` + 1 bytes even if the file grows.
std::optional<std::string> read_input_file(const std::filesystem::path& path,
                                           std::uintmax_t max_bytes, std::string& bytes);

/// The whole of `path`, read as read_input_file does. On refusal throws `Failure` (an
/// exception type constructed from a message) as one line "<what> <path>: <why>", e.g.
/// "config file /dev/zero: not a regular file (a FIFO, a device or a socket)".
template <class Failure>
std::string read_input_file(const std::filesystem::path& path, std::string_view what,
                            std::uintmax_t max_bytes) {
  std::string bytes;
  if (const std::optional<std::string> problem = read_input_file(path, max_bytes, bytes)) {
    throw Failure(std::string(what) + " " + path.string() + ": " + *problem);
  }
  return bytes;
}

}  // namespace upkie_rl
