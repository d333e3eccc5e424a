#pragma once
/// @file
/// Whole episodes of an environment with a controller, and their summary: the loop that
/// evaluations (`upkie-rl evaluate`, the final evaluation of a sweep) share.

#include <cstdint>
#include <span>
#include <vector>

#include "envs/controllers/controller.hpp"
#include "envs/core/env.hpp"
#include "envs/tasks/velocity_tracking.hpp"

namespace upkie_rl {

/// How one episode went.
struct EpisodeOutcome {
  double total_reward = 0.0;
  int length = 0;           ///< Steps taken.
  bool terminated = false;  ///< The task ended it (a fall); otherwise a time limit did.
  /// Velocity tasks: tracking errors over the episode (no steps otherwise).
  VelocityTracking tracking;
};

/// Resets `env` with `seed`, then steps it with `controller` until the episode ends or
/// `max_steps` steps. `observation` and `action` are buffers of the env's spaces' sizes.
EpisodeOutcome run_episode(Env& env, Controller& controller, std::uint64_t seed, int max_steps,
                           std::span<float> observation, std::span<float> action);

/// Statistics of episodes; a success is an episode that was not terminated.
struct EpisodeSummary {
  int episodes = 0;
  int successes = 0;
  double mean_return = 0.0;
  double std_return = 0.0;  ///< Population standard deviation.
  double mean_length = 0.0;
  /// Velocity tasks: the tracking errors pooled over every step of every episode.
  bool has_tracking = false;
  VelocityTracking tracking;
  /// Share of episodes that were terminated (falls).
  double fall_rate = 0.0;
};

EpisodeSummary summarize_episodes(const std::vector<EpisodeOutcome>& outcomes);

}  // namespace upkie_rl
