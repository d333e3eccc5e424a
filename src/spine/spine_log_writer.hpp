#pragma once
/// @file
/// SpineLogWriter: a spine log (spine/spine_log.hpp) written cycle by cycle.

#include <cstdio>
#include <filesystem>
#include <msgpack.hpp>

#include "spine/spine_log.hpp"

namespace upkie_rl {

/// Appends one dictionary {"action": {"servo": {joint: {...}}}, "observation": {...},
/// "time": t} per call, keys sorted and every number a float64, as Upkie's spines log their
/// working dictionary. The `mpacklog` Python package (`mpacklog.read_log`) reads the file.
class SpineLogWriter {
 public:
  /// Opens (truncates) `path`.
  /// @throws RobotLogError naming the path when it cannot be written.
  explicit SpineLogWriter(const std::filesystem::path& path);
  ~SpineLogWriter();
  SpineLogWriter(const SpineLogWriter&) = delete;
  SpineLogWriter& operator=(const SpineLogWriter&) = delete;

  /// Writes the cycle of `observation` (its time) with the commands `action` in force.
  /// Allocates nothing once the buffer has grown to one dictionary.
  /// @throws RobotLogError on a write error.
  void write(const Observation& observation, const ServoAction& action);

  /// Flushes and closes; @throws RobotLogError on a write error.
  void close();

 private:
  std::filesystem::path path_;
  std::FILE* file_ = nullptr;
  msgpack::sbuffer buffer_;
  msgpack::sbuffer action_buffer_;
};

}  // namespace upkie_rl
