#pragma once
/// @file
/// The record files of `upkie-rl rollout --record` (envs/records/episode_recorder.hpp) read back
/// for `upkie-rl render` and `upkie-rl view`.

#include <cstdint>
#include <filesystem>
#include <istream>
#include <optional>
#include <string>
#include <vector>

#include "envs/records/episode_recorder.hpp"
#include "envs/records/record_file_error.hpp"
#include "envs/tasks/velocity_command.hpp"
#include "render/robot_renderer.hpp"

namespace upkie_rl {

/// What `upkie-rl render` and `upkie-rl view` need of one row of a record file.
struct RecordedStep {
  int episode = 0;
  int step = 0;
  double time = 0.0;    ///< [s]
  double reward = 0.0;  ///< Of the step taken from this state.
  RobotPose pose;
  /// As measured; files written before these columns existed give the pitch of the
  /// ground-truth orientation and base_x.
  double pitch = 0.0;
  double ground_position = 0.0;
  std::vector<double> action;  ///< In the order of RecordFile::action_names.
  /// Velocity tasks: the command the controller saw and the measured base velocity, when the
  /// file has their columns (kCommandColumns, kMeasuredVelocityColumns).
  std::optional<VelocityCommand> command;
  std::optional<BaseVelocity> measured;
};

/// The rows of a record file, and the names of its action columns (without "action.").
struct RecordFile {
  std::vector<std::string> action_names;
  std::vector<RecordedStep> steps;
  /// Whether the file has the velocity task's columns. The reader takes that group for every
  /// row or for none (RecordedStep::command and measured), so the first step says.
  bool has_velocity() const { return !steps.empty() && steps.front().command.has_value(); }
};

/// Largest record file read: a row is about 400 bytes, so 1 GiB holds some 2.5 million steps
/// (3.5 hours at 200 Hz), far beyond a rollout worth watching, and stays finite.
inline constexpr std::uintmax_t kMaxRecordFileBytes = std::uintmax_t{1} << 30;

/// Reads a record file written by EpisodeRecorder (any environment), at most
/// kMaxRecordFileBytes, refusing a FIFO or a device.
/// @throws RecordFileError naming the file, and the line and column at fault: a missing
///         column, a value that is not a number, a row of the wrong length, no ground truth
///         (a spine run), or no rows at all.
RecordFile read_record_file(const std::filesystem::path& path);

/// The same, from a stream already open; `name` stands for the file in messages (the
/// fuzz target reads its inputs from memory through it).
/// @throws RecordFileError as above.
RecordFile read_record_file(std::istream& in, const std::string& name);

}  // namespace upkie_rl
