#pragma once
/// @file
/// SyncVectorEnv: n environments stepped one after the other on the calling thread
/// (SB3's DummyVecEnv).

#include "vec/env_batch_vector_env.hpp"

namespace upkie_rl {

class SyncVectorEnv final : public EnvBatchVectorEnv {
 public:
  explicit SyncVectorEnv(std::vector<std::unique_ptr<Env>> envs,
                         AutoresetMode autoreset_mode = AutoresetMode::kSameStep)
      : EnvBatchVectorEnv(std::move(envs), autoreset_mode) {}

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
};

}  // namespace upkie_rl
