#pragma once
/// @file
/// DriveLoop: the simulation loop of `upkie-rl drive`. It steps a velocity task in real time
/// with its controller, follows the commands a page sends (DriveControl), resets, pauses and
/// pushes when the page asks, starts a new episode after a fall, and streams every step to
/// the viewer (and to a record file).

#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

#include "cli/live_view.hpp"
#include "cli/velocity_view.hpp"
#include "envs/controllers/controller.hpp"
#include "envs/kinds/velocity_env.hpp"
#include "envs/records/episode_recorder.hpp"
#include "view/drive_control.hpp"

namespace upkie_rl::apps {

/// Settings of a DriveLoop.
struct DriveLoopSettings {
  std::uint64_t seed = 0;      ///< Episode e starts from seed + e.
  double duration = 0.0;       ///< Simulated seconds to run; 0: until stopped.
  double push_force = 30.0;    ///< Of a page's push [N].
  double push_duration = 0.2;  ///< [s]
};

/// What a drive did.
struct DriveSummary {
  long steps = 0;
  int episodes = 0;  ///< Started.
  int falls = 0;     ///< Episodes that ended in a termination.
  int pushes = 0;
  double simulated_time = 0.0;  ///< [s]
};

/// The velocity task inside `env` (environment `env_id`), which a drive steers.
/// @throws std::invalid_argument naming `env_id` when `env` is not a velocity task.
VelocityEnv& drive_velocity_env(Env& env, const std::string& env_id);

class DriveLoop {
 public:
  /// Everything is borrowed and must outlive the loop; `recorder` may be null.
  /// @param velocity The velocity task inside `env` (drive_velocity_env).
  DriveLoop(Env& env, VelocityEnv& velocity, Controller& controller, LiveView& view,
            DriveControl& drive, EpisodeRecorder* recorder, const DriveLoopSettings& settings);

  /// Runs until `stop` becomes true or the duration has passed.
  DriveSummary run(const std::atomic<bool>& stop);

 private:
  void start_episode();
  /// Takes the page's inputs, waiting while the run is paused; false when stopped meanwhile.
  bool take_inputs(const std::atomic<bool>& stop, DriveInputs& inputs);
  void push(double heading);
  /// One step of the env; starts a new episode when this one ended.
  void step();

  Env& env_;
  VelocityEnv& velocity_;
  Controller& controller_;
  LiveView& view_;
  DriveControl& drive_;
  EpisodeRecorder* recorder_;
  DriveLoopSettings settings_;
  std::vector<float> observation_;
  std::vector<float> action_;
  std::array<double, kVelocityViewFields> view_fields_{};
  int episode_ = -1;
  int length_ = 0;
  double episode_return_ = 0.0;
  DriveSummary summary_;
};

}  // namespace upkie_rl::apps
