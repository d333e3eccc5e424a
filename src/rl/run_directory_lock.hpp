#pragma once
/// @file
/// The lock a trainer holds on its run directory for as long as it trains there: a second
/// trainer in the same directory (a second `upkie-rl train --run-dir`, `--resume`, or a
/// sweep task started twice) is refused instead of interleaving checkpoints and logs. The
/// lock is an flock(2) on `<run dir>/.lock`, which the kernel releases when the process
/// ends, however it ends, so a killed trainer leaves no stale lock.

#include <filesystem>

namespace upkie_rl {

class RunDirectoryLock {
 public:
  /// Locks `run_dir` (created if needed). Throws std::runtime_error naming the directory
  /// and the process holding it when another process holds it.
  explicit RunDirectoryLock(const std::filesystem::path& run_dir);
  ~RunDirectoryLock();
  RunDirectoryLock(const RunDirectoryLock&) = delete;
  RunDirectoryLock& operator=(const RunDirectoryLock&) = delete;

 private:
  int descriptor_ = -1;
};

/// Removes the temporary files (`*.tmp.<pid>`) that interrupted checkpoint and log writes
/// left in `run_dir` and its checkpoints/ folder; call with the directory locked. Returns
/// how many it removed.
int remove_stale_temporaries(const std::filesystem::path& run_dir);

}  // namespace upkie_rl
