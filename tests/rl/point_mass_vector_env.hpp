#pragma once
/// @file
/// A tiny vector environment for testing PPO without physics: n point masses on a line.
/// Observation [x], action [u] in [-1, 1], x ← x + 0.1·u; reward 1 − x²; terminated when
/// |x| > 1.5, truncated after `max_steps` steps. A good policy drives x to 0. Episodes start
/// at x drawn in [reset_low, 1]. Its mirror (x -> -x, u -> -u) is declared on request.

#include <cmath>
#include <cstdint>
#include <optional>
#include <random>
#include <span>
#include <vector>

#include "vec/vector_env.hpp"

namespace upkie_rl::testing {

class PointMassVectorEnv final : public VectorEnv {
 public:
  explicit PointMassVectorEnv(std::size_t num_envs, std::int64_t max_steps = 50,
                              double reset_low = -1.0)
      : max_steps_(max_steps),
        reset_low_(reset_low),
        x_(num_envs),
        steps_(num_envs),
        returns_(num_envs),
        generators_(num_envs) {
    observation_space_.low = {-INFINITY};
    observation_space_.high = {INFINITY};
    observation_space_.names = {"x"};
    action_space_.low = {-1.0f};
    action_space_.high = {1.0f};
    action_space_.names = {"u"};
    result_.observations.resize(num_envs);
    result_.rewards.resize(num_envs);
    result_.terminated.resize(num_envs);
    result_.truncated.resize(num_envs);
    result_.final_observations.resize(num_envs);
    result_.episode_returns.resize(num_envs);
    result_.episode_lengths.resize(num_envs);
  }

  std::size_t num_envs() const override { return x_.size(); }
  const BoxSpace& observation_space() const override { return observation_space_; }
  const BoxSpace& action_space() const override { return action_space_; }

  std::span<const float> reset(std::optional<std::uint64_t> seed) override {
    for (std::size_t i = 0; i < x_.size(); ++i) {
      if (seed) generators_[i].seed(*seed + i);
      reset_one(i);
    }
    return result_.observations;
  }

  const VectorStep& step(std::span<const float> actions) override {
    ++total_steps_;
    for (std::size_t i = 0; i < x_.size(); ++i) {
      const double u = std::clamp(static_cast<double>(actions[i]), -1.0, 1.0);
      x_[i] += 0.1 * u;
      const double reward = 1.0 - x_[i] * x_[i];
      ++steps_[i];
      returns_[i] += reward;
      result_.rewards[i] = static_cast<float>(reward);
      result_.terminated[i] = std::abs(x_[i]) > 1.5;
      result_.truncated[i] = steps_[i] >= max_steps_;
      if (result_.terminated[i] || result_.truncated[i]) {
        result_.final_observations[i] = static_cast<float>(x_[i]);
        result_.episode_returns[i] = returns_[i];
        result_.episode_lengths[i] = steps_[i];
        reset_one(i);
      } else {
        result_.observations[i] = static_cast<float>(x_[i]);
      }
    }
    return result_;
  }

  std::int64_t total_steps() const { return total_steps_; }

  /// Declares the mirror x -> -x, u -> -u (mirror_symmetry()).
  void declare_mirror() {
    mirror_ = MirrorSymmetry{SignedPermutation({0}, {true}, "observation"),
                             SignedPermutation({0}, {true}, "action")};
  }
  const MirrorSymmetry* mirror_symmetry() const override { return mirror_ ? &*mirror_ : nullptr; }

 private:
  void reset_one(std::size_t i) {
    x_[i] = std::uniform_real_distribution<double>(reset_low_, 1.0)(generators_[i]);
    steps_[i] = 0;
    returns_[i] = 0.0;
    result_.observations[i] = static_cast<float>(x_[i]);
  }

  std::int64_t max_steps_;
  double reset_low_;
  std::optional<MirrorSymmetry> mirror_;
  BoxSpace observation_space_;
  BoxSpace action_space_;
  std::vector<double> x_;
  std::vector<std::int64_t> steps_;
  std::vector<double> returns_;
  std::vector<std::mt19937_64> generators_;
  VectorStep result_;
  std::int64_t total_steps_ = 0;
};

}  // namespace upkie_rl::testing
