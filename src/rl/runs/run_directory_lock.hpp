#pragma once
/// @file
/// The lock a trainer holds on its run directory for as long as it trains there: a second
/// trainer in the same directory (a second `upkie-rl train --run-dir`, `--resume`, or a
/// sweep task started twice) is refused instead of interleaving checkpoints and logs. The
/// lock is an flock(2) on `<run dir>/.lock`, which the kernel releases when the process
/// ends, however it ends, so a killed trainer leaves no stale lock.

#include <filesystem>
#include <vector>

namespace upkie_rl {

class RunDirectoryLock {
 public:
  /// Locks `run_dir` (created if needed). Throws std::runtime_error naming the directory
  /// and the process holding it when another process holds it.
  explicit RunDirectoryLock(const std::filesystem::path& run_dir);
  /// Releases the lock. Unless keep() was called, a lock taken on a directory that was
  /// absent or empty also removes what the refused start created: `.lock`, the files
  /// passed to note_created() and the directories the constructor created (when empty).
  ~RunDirectoryLock();
  /// Records a file this process created in the directory before keep().
  void note_created(const std::filesystem::path& file);
  /// The run has started (its training began): the directory and its files stay.
  void keep() { kept_ = true; }
  RunDirectoryLock(const RunDirectoryLock&) = delete;
  RunDirectoryLock& operator=(const RunDirectoryLock&) = delete;

 private:
  void remove_created() const;

  std::filesystem::path run_dir_;
  int descriptor_ = -1;
  bool kept_ = false;
  bool started_empty_ = false;           // run_dir_ was absent or empty
  std::filesystem::path first_created_;  // the outermost directory the lock created
  std::vector<std::filesystem::path> created_files_;
};

/// Whether `directory` is an upkie-rl run: one a trainer started in (it holds `.lock`).
bool is_run_directory(const std::filesystem::path& directory);

/// Removes the temporary files (`*.tmp.<pid>`) that interrupted checkpoint and log writes
/// left in `run_dir` and its checkpoints/ folder; call with the directory locked. Returns
/// how many it removed.
int remove_stale_temporaries(const std::filesystem::path& run_dir);

}  // namespace upkie_rl
