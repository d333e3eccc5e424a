#pragma once
/// @file
/// TimeLimit: truncates episodes after a number of steps (Gymnasium's TimeLimit).

#include <memory>
#include <stdexcept>
#include <string>

#include "envs/wrappers/env_wrapper.hpp"

namespace upkie_rl {

/// Sets `truncated` on the step that brings the episode length to max_episode_steps,
/// independently of `terminated`.
class TimeLimit final : public EnvWrapper {
 public:
  /// @throws std::invalid_argument on a null env or a non-positive limit.
  TimeLimit(std::unique_ptr<Env> env, int max_episode_steps)
      : EnvWrapper(std::move(env), "TimeLimit"), max_episode_steps_(max_episode_steps) {
    if (max_episode_steps_ <= 0) {
      throw std::invalid_argument("TimeLimit: max_episode_steps must be positive, got " +
                                  std::to_string(max_episode_steps_));
    }
  }

  int max_episode_steps() const { return max_episode_steps_; }
  /// Steps taken since the last reset.
  int elapsed_steps() const { return elapsed_steps_; }

  void reset(std::optional<std::uint64_t> seed, std::span<float> observation) override {
    env_->reset(seed, observation);
    elapsed_steps_ = 0;
  }
  StepResult step(std::span<const float> action, std::span<float> observation) override {
    StepResult result = env_->step(action, observation);
    ++elapsed_steps_;
    if (elapsed_steps_ >= max_episode_steps_) result.truncated = true;
    return result;
  }

 private:
  int max_episode_steps_;
  int elapsed_steps_ = 0;
};

}  // namespace upkie_rl
