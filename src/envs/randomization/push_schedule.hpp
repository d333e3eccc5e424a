#pragma once
/// @file
/// PushSchedule: when the pushes of PushSettings happen in an episode, and their force.

#include <cstdint>
#include <random>

#include <Eigen/Core>

#include "envs/randomization/perturbation_settings.hpp"

namespace upkie_rl {

/// Draws each push when its window opens: its start within the window, magnitude and
/// direction. Deterministic given the seed of reset().
class PushSchedule {
 public:
  /// Starts an episode: pushes of `settings`, magnitudes multiplied by `scale`.
  void reset(const PushSettings& settings, double scale, std::uint64_t seed);

  /// The force on the base [N, world frame] during the agent step that starts at `time`
  /// [s], for a robot heading `yaw` [rad] (read when a push starts).
  Eigen::Vector3d force(double time, double yaw);

 private:
  void draw_push(int window);

  PushSettings settings_;
  double scale_ = 1.0;
  std::mt19937_64 generator_{0};
  int window_ = -1;                                  ///< Window of the push drawn last.
  double push_start_ = 0.0;                          ///< [s]
  double magnitude_ = 0.0;                           ///< [N]
  double angle_ = 0.0;                               ///< Direction relative to the heading [rad].
  bool started_ = false;                             ///< Whether the drawn push has begun.
  Eigen::Vector3d force_ = Eigen::Vector3d::Zero();  ///< Of the push under way.
};

}  // namespace upkie_rl
