#include "rl/runs/run_directory_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

#include "rl/runs/run_file_error.hpp"

namespace upkie_rl {

namespace {

constexpr const char* kLockName = ".lock";

/// The outermost of `directory` and its ancestors that does not exist yet (empty when
/// `directory` exists): what create_directories(directory) creates.
std::filesystem::path first_missing(const std::filesystem::path& directory) {
  std::error_code error;
  std::filesystem::path missing;
  for (std::filesystem::path path = directory;
       !path.empty() && !std::filesystem::exists(path, error); path = path.parent_path()) {
    missing = path;
    if (path == path.parent_path()) break;
  }
  return missing;
}

}  // namespace

bool is_run_directory(const std::filesystem::path& directory) {
  std::error_code error;
  return std::filesystem::exists(directory / kLockName, error);
}

RunDirectoryLock::RunDirectoryLock(const std::filesystem::path& run_dir)
    // "runs/x/" names runs/x: without its trailing separator, parent_path() climbs.
    : run_dir_(run_dir.has_filename() || !run_dir.has_parent_path() ? run_dir
                                                                    : run_dir.parent_path()) {
  std::error_code error;
  first_created_ = first_missing(run_dir_);
  started_empty_ = !first_created_.empty() || std::filesystem::is_empty(run_dir, error);
  std::filesystem::create_directories(run_dir);
  const std::filesystem::path path = run_dir / kLockName;
  descriptor_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (descriptor_ < 0) {
    throw RunFileError("cannot open " + path.string() + ": " + std::strerror(errno));
  }
  if (::flock(descriptor_, LOCK_EX | LOCK_NB) != 0) {
    char holder[32] = {};
    const ssize_t read = ::pread(descriptor_, holder, sizeof(holder) - 1, 0);
    ::close(descriptor_);
    descriptor_ = -1;
    started_empty_ = false;  // the directory is the holder's: nothing of it is removed
    throw RunFileError("run directory " + run_dir.string() + " is in use by another trainer" +
                       (read > 0 ? " (process " + std::string(holder, read) + ")" : ""));
  }
  const std::string pid = std::to_string(::getpid());
  if (::ftruncate(descriptor_, 0) == 0) {
    [[maybe_unused]] const ssize_t written = ::pwrite(descriptor_, pid.data(), pid.size(), 0);
  }
}

RunDirectoryLock::~RunDirectoryLock() {
  // Removed while still locked, so that no other trainer starts in a directory half gone.
  if (!kept_ && started_empty_ && descriptor_ >= 0) remove_created();
  if (descriptor_ >= 0) ::close(descriptor_);  // releases the flock
}

void RunDirectoryLock::note_created(const std::filesystem::path& file) {
  created_files_.push_back(file);
}

void RunDirectoryLock::remove_created() const {
  std::error_code error;
  for (const std::filesystem::path& file : created_files_) std::filesystem::remove(file, error);
  std::filesystem::remove(run_dir_ / kLockName, error);
  if (first_created_.empty()) return;
  // Innermost first; remove() leaves a directory that is not empty.
  for (std::filesystem::path path = run_dir_;; path = path.parent_path()) {
    if (!std::filesystem::remove(path, error)) return;
    if (path == first_created_ || path == path.parent_path()) return;
  }
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
