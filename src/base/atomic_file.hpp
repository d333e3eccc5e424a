#pragma once
/// @file
/// Writing a whole file so that a reader never sees half of it: the bytes go to a
/// temporary file beside it, are flushed to disk, and the temporary is renamed over the
/// destination (a rename within one directory is atomic on POSIX file systems).

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <system_error>

namespace upkie_rl {

/// The temporary `write_file_atomically` writes first: `path` + ".tmp." + the process id,
/// so that two processes writing the same file do not share one.
inline std::filesystem::path atomic_temporary_path(const std::filesystem::path& path) {
  return path.string() + ".tmp." + std::to_string(::getpid());
}

/// Writes `bytes` to `path` through atomic_temporary_path(path), fsync and rename; creates
/// the parent directories. On failure removes the temporary and throws `Failure` (an
/// exception type constructed from a message): "cannot create T", "cannot write T" or
/// "cannot rename T to P: reason".
template <class Failure>
void write_file_atomically(const std::filesystem::path& path, std::string_view bytes) {
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  const std::filesystem::path temporary = atomic_temporary_path(path);
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw Failure("cannot create " + temporary.string());
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.flush();
    if (!out) {
      out.close();
      std::filesystem::remove(temporary);
      throw Failure("cannot write " + temporary.string());
    }
  }
  // Flush to disk before the rename so a crash cannot leave a renamed, empty file.
  if (FILE* handle = std::fopen(temporary.c_str(), "rb")) {
    ::fsync(fileno(handle));
    std::fclose(handle);
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) {
    std::filesystem::remove(temporary);
    throw Failure("cannot rename " + temporary.string() + " to " + path.string() + ": " +
                  error.message());
  }
}

}  // namespace upkie_rl
