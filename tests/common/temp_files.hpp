#pragma once
/// @file
/// Files for the tests that write and damage them: a per-process temporary folder, and the
/// bytes of a file read and written whole.

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace upkie_rl::testing {

/// `name` in a folder of this test program's own (made on first use).
inline std::filesystem::path temp_path(const std::string& name,
                                       const std::string& folder = "upkie_rl_test") {
  const auto directory =
      std::filesystem::temp_directory_path() / (folder + "_" + std::to_string(::getpid()));
  std::filesystem::create_directories(directory);
  return directory / name;
}

/// Makes a FIFO at `path` (its folder too), replacing what was there: a file whose reader
/// blocks until a writer comes, which none does. Returns `path`; empty if mkfifo failed.
inline std::filesystem::path make_fifo(const std::filesystem::path& path) {
  std::filesystem::create_directories(path.parent_path());
  std::filesystem::remove(path);
  return ::mkfifo(path.c_str(), 0600) == 0 ? path : std::filesystem::path();
}

inline std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

inline void write_bytes(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

}  // namespace upkie_rl::testing
