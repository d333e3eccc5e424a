#pragma once
/// @file
/// FlightRecorder: every cycle of the robot runner to a record file.

#include <array>
#include <filesystem>
#include <span>

#include "agent/supervisor_state.hpp"
#include "envs/records/episode_recorder.hpp"

namespace upkie_rl {

/// The runner's columns after those of `upkie-rl rollout --record`: the supervisor state
/// (SupervisorState's value), the cycle's period and the time the policy took [s], and 1 when
/// the cycle missed its deadline.
inline constexpr std::array<const char*, 4> kFlightRecorderColumns = {
    "supervisor_state", "loop_period", "policy_time", "deadline_miss"};

/// A record file of `upkie-rl rollout --record` (one episode, 0) with the runner's own
/// columns, so that `upkie-rl view` and `upkie-rl render` replay a run of the runner.
class FlightRecorder {
 public:
  /// Opens (truncates) `path`.
  /// @throws std::runtime_error naming the path when it cannot be written.
  explicit FlightRecorder(const std::filesystem::path& path) : recorder_(path) {}

  void write_header(const Env& env);

  /// Before the step: the observation the policy saw.
  void before_step(const Env& env, std::span<const float> observation) {
    recorder_.before_step(env, observation);
  }

  /// After the step: the action, the step's result and the runner's columns.
  void after_step(int cycle, std::span<const float> action, const StepResult& result,
                  SupervisorState state, double loop_period, double policy_time,
                  bool deadline_miss);

  /// Flushes; @throws std::runtime_error on a write error.
  void close() { recorder_.close(); }

 private:
  EpisodeRecorder recorder_;
};

}  // namespace upkie_rl
