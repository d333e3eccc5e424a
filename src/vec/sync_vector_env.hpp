#pragma once
/// @file
/// SyncVectorEnv: n environments stepped one after the other on the calling thread
/// (SB3's DummyVecEnv).

#include "vec/env_batch.hpp"
#include "vec/vector_env.hpp"

namespace upkie_rl {

class SyncVectorEnv final : public VectorEnv {
 public:
  explicit SyncVectorEnv(std::vector<std::unique_ptr<Env>> envs,
                         AutoresetMode autoreset_mode = AutoresetMode::kSameStep)
      : batch_(std::move(envs), autoreset_mode) {}

  std::size_t num_envs() const override { return batch_.size(); }
  const BoxSpace& observation_space() const override { return batch_.observation_space(); }
  const BoxSpace& action_space() const override { return batch_.action_space(); }
  std::span<const float> reset(std::optional<std::uint64_t> seed) override {
    batch_.reset(0, batch_.size(), seed);
    batch_.mark_reset();
    return batch_.result().observations;
  }
  const VectorStep& step(std::span<const float> actions) override {
    batch_.check_step(actions);
    batch_.step(0, batch_.size(), actions);
    return batch_.result();
  }

  /// Environment i (e.g. for its full observation).
  const Env& env(std::size_t i) const { return batch_.env(i); }
  void set_randomization_scale(double scale) override { batch_.set_randomization_scale(scale); }
  std::span<const std::string_view> reward_term_names() const override {
    return batch_.env(0).reward_term_names();
  }
  const Observation* full_observation(std::size_t i) const override {
    return batch_.env(i).full_observation();
  }

 private:
  EnvBatch batch_;
};

}  // namespace upkie_rl
