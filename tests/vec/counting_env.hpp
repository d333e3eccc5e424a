#pragma once
/// @file
/// A tiny deterministic Env for vector-env tests: observation [seed, step, last action],
/// reward = the action, episodes end after `length` steps (terminated) or, with
/// `truncate`, truncated instead.

#include <optional>

#include "envs/core/env.hpp"

namespace upkie_rl::testing {

class CountingEnv final : public Env {
 public:
  explicit CountingEnv(int length = 3, bool truncate = false)
      : length_(length), truncate_(truncate) {
    observation_space_.add("seed", -1e9f, 1e9f);
    observation_space_.add("step", 0.0f, 1e9f);
    observation_space_.add("action", -1e9f, 1e9f);
    action_space_.add("a", -100.0f, 100.0f);
  }
  const BoxSpace& observation_space() const override { return observation_space_; }
  const BoxSpace& action_space() const override { return action_space_; }
  void reset(std::optional<std::uint64_t> seed, std::span<float> observation) override {
    if (seed)
      seed_ = static_cast<float>(*seed);
    else
      seed_ += 1000.0f;  // Unseeded resets continue the "generator".
    step_ = 0;
    observation[0] = seed_;
    observation[1] = 0.0f;
    observation[2] = 0.0f;
    ++resets;
  }
  StepResult step(std::span<const float> action, std::span<float> observation) override {
    float clamped = 0.0f;
    clamp_to_space(action_space_, action, std::span<float>(&clamped, 1));
    ++step_;
    observation[0] = seed_;
    observation[1] = static_cast<float>(step_);
    observation[2] = clamped;
    StepResult result;
    result.reward = clamped;
    if (step_ >= length_) (truncate_ ? result.truncated : result.terminated) = true;
    return result;
  }
  const Observation* full_observation() const override { return nullptr; }
  double timestep() const override { return 0.005; }
  int physics_steps_per_step() const override { return 0; }

  int resets = 0;

 private:
  int length_;
  bool truncate_;
  BoxSpace observation_space_;
  BoxSpace action_space_;
  float seed_ = 0.0f;
  int step_ = 0;
};

}  // namespace upkie_rl::testing
