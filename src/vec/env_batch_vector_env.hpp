#pragma once
/// @file
/// EnvBatchVectorEnv: the part of a vector env over an EnvBatch that does not step, written
/// once for SyncVectorEnv and ThreadPoolVectorEnv, which differ only in how they reset and
/// step the batch.
///
/// Why a base class: the forwarding methods are VectorEnv's virtual interface anyway, and
/// declared final here so that calls through the concrete types need no indirection. The
/// hot loop is untouched: each subclass's step() calls EnvBatch::step directly, with no
/// virtual call per environment and no allocation.

#include <memory>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

#include "vec/env_batch.hpp"
#include "vec/vector_env.hpp"

namespace upkie_rl {

class EnvBatchVectorEnv : public VectorEnv {
 public:
  std::size_t num_envs() const final { return batch_.size(); }
  const BoxSpace& observation_space() const final { return batch_.observation_space(); }
  const BoxSpace& action_space() const final { return batch_.action_space(); }
  void set_randomization_scale(double scale) final { batch_.set_randomization_scale(scale); }
  std::span<const std::string_view> reward_term_names() const final {
    return batch_.env(0).reward_term_names();
  }
  const MirrorSymmetry* mirror_symmetry() const final { return batch_.env(0).mirror_symmetry(); }
  const Observation* full_observation(std::size_t i) const final {
    return batch_.env(i).full_observation();
  }

  /// Environment i (e.g. for its full observation).
  const Env& env(std::size_t i) const { return batch_.env(i); }

 protected:
  /// @throws std::invalid_argument as EnvBatch's constructor.
  EnvBatchVectorEnv(std::vector<std::unique_ptr<Env>> envs, AutoresetMode autoreset_mode)
      : batch_(std::move(envs), autoreset_mode) {}

  EnvBatch batch_;
};

}  // namespace upkie_rl
