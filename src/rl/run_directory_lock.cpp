#include "rl/run_directory_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

namespace upkie_rl {

RunDirectoryLock::RunDirectoryLock(const std::filesystem::path& run_dir) {
  std::filesystem::create_directories(run_dir);
  const std::filesystem::path path = run_dir / ".lock";
  descriptor_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (descriptor_ < 0) {
    throw std::runtime_error("cannot open " + path.string() + ": " + std::strerror(errno));
  }
  if (::flock(descriptor_, LOCK_EX | LOCK_NB) != 0) {
    char holder[32] = {};
    const ssize_t read = ::pread(descriptor_, holder, sizeof(holder) - 1, 0);
    ::close(descriptor_);
    descriptor_ = -1;
    throw std::runtime_error("run directory " + run_dir.string() +
                             " is in use by another trainer" +
                             (read > 0 ? " (process " + std::string(holder, read) + ")" : ""));
  }
  const std::string pid = std::to_string(::getpid());
  if (::ftruncate(descriptor_, 0) == 0) {
    [[maybe_unused]] const ssize_t written = ::pwrite(descriptor_, pid.data(), pid.size(), 0);
  }
}

RunDirectoryLock::~RunDirectoryLock() {
  if (descriptor_ >= 0) ::close(descriptor_);  // releases the flock
}

int remove_stale_temporaries(const std::filesystem::path& run_dir) {
  int removed = 0;
  for (const std::filesystem::path& directory : {run_dir, run_dir / "checkpoints"}) {
    std::error_code error;
    for (const auto& entry : std::filesystem::directory_iterator(directory, error)) {
      const std::string name = entry.path().filename().string();
      if (entry.is_regular_file(error) && name.find(".tmp.") != std::string::npos &&
          std::filesystem::remove(entry.path(), error)) {
        ++removed;
      }
    }
  }
  return removed;
}

}  // namespace upkie_rl
