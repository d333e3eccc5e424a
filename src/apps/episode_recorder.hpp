#pragma once
/// @file
/// EpisodeRecorder: the CSV file of `upkie-rl rollout --record`.

#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <span>
#include <vector>

#include "envs/env.hpp"
#include "render/robot_renderer.hpp"

namespace upkie_rl::apps {

/// Columns of the simulator's ground truth, before the six joint angles (kServoNames).
inline constexpr std::array<const char*, 7> kGroundTruthColumns = {
    "base_x", "base_y", "base_z", "base_qw", "base_qx", "base_qy", "base_qz"};

/// Columns after the joint angles: the pitch and ground position the robot measures.
inline constexpr std::array<const char*, 2> kMeasuredColumns = {"pitch", "ground_position"};

/// One row per step: episode, step, t, each observation component by name, each action
/// component by name ("action.<name>"), reward, terminated, truncated, then the simulator's
/// ground truth base_x, base_y, base_z, base_qw, base_qx, base_qy, base_qz and the six joint
/// angles by joint name (NaN when the backend has no ground truth), then the base pitch and
/// the wheel odometry's ground position. A row holds the observation the controller saw at
/// time t, the ground truth at that time, the action it chose, and the reward and flags of
/// the step that action made.
class EpisodeRecorder {
 public:
  /// Opens (truncates) `path`, so that a bad path is refused before anything runs.
  /// @throws std::runtime_error naming the path when it cannot be written.
  explicit EpisodeRecorder(const std::filesystem::path& path);

  /// Writes the header row for `env`'s spaces.
  void write_header(const Env& env);

  /// Remembers t, the observation and the ground truth before a step.
  void before_step(const Env& env, std::span<const float> observation);

  /// Writes the row of the step.
  void after_step(int episode, int step, std::span<const float> action, const StepResult& result);

  /// Flushes; @throws std::runtime_error naming the path on a write error.
  void close();

 private:
  std::filesystem::path path_;
  std::ofstream out_;
  std::vector<float> observation_;
  double time_ = 0.0;
  std::array<double, 7 + 6 + 2> ground_truth_{};
};

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
};

/// The rows of a record file, and the names of its action columns (without "action.").
struct RecordFile {
  std::vector<std::string> action_names;
  std::vector<RecordedStep> steps;
};

/// Reads a record file written by EpisodeRecorder (any environment).
/// @throws std::runtime_error naming the file, and the line and column at fault: a missing
///         column, a value that is not a number, a row of the wrong length, no ground truth
///         (a spine run), or no rows at all.
RecordFile read_record_file(const std::filesystem::path& path);

}  // namespace upkie_rl::apps
