#pragma once
/// @file
/// EnvBatch: n environments and their VectorStep buffers, stepped by index range. The one
/// place the auto-reset semantics live; SyncVectorEnv steps the whole range, the thread pool
/// gives each worker a fixed part, so both give the same results.

#include <memory>
#include <span>
#include <vector>

#include "envs/core/env.hpp"
#include "vec/vector_env.hpp"

namespace upkie_rl {

class EnvBatch {
 public:
  /// @throws std::invalid_argument on an empty list, a null env, or envs whose spaces differ
  ///         in size.
  explicit EnvBatch(std::vector<std::unique_ptr<Env>> envs,
                    AutoresetMode autoreset_mode = AutoresetMode::kSameStep);

  std::size_t size() const { return envs_.size(); }
  std::size_t observation_size() const { return observation_size_; }
  std::size_t action_size() const { return action_size_; }
  const BoxSpace& observation_space() const { return envs_.front()->observation_space(); }
  const BoxSpace& action_space() const { return envs_.front()->action_space(); }
  Env& env(std::size_t i) { return *envs_[i]; }
  const Env& env(std::size_t i) const { return *envs_[i]; }

  /// Resets envs [begin, end), env i with seed + i (unseeded without a seed), into
  /// result().observations.
  void reset(std::size_t begin, std::size_t end, std::optional<std::uint64_t> seed);
  /// Records that every env was reset (step() is refused before), once all ranges are done.
  void mark_reset() { was_reset_ = true; }
  void set_randomization_scale(double scale) {
    for (auto& env : envs_) env->set_randomization_scale(scale);
  }

  /// Steps envs [begin, end) with their rows of `actions`; an env whose episode ends keeps
  /// its last observation in final_observations, its raw return and length in
  /// episode_returns / episode_lengths, and is reset (unseeded: its generator continues)
  /// in this step or the next one, as the autoreset mode says.
  void step(std::size_t begin, std::size_t end, std::span<const float> actions);

  /// Throws unless `actions` has size() x action_size() components and reset() was called.
  void check_step(std::span<const float> actions) const;

  const VectorStep& result() const { return result_; }
  AutoresetMode autoreset_mode() const { return autoreset_mode_; }

 private:
  /// Adds env i's last reward terms to its episode sums.
  void accumulate_reward_terms(std::size_t i);

  std::vector<std::unique_ptr<Env>> envs_;
  AutoresetMode autoreset_mode_;
  std::vector<std::uint8_t> needs_reset_;  // kNextStep: the episode ended at the last step.
  std::size_t observation_size_;
  std::size_t action_size_;
  VectorStep result_;
  std::vector<double> running_returns_;
  std::vector<std::int64_t> running_lengths_;
  std::size_t num_terms_ = 0;          // Env::reward_term_names().size()
  std::vector<double> running_terms_;  // num_envs x num_terms_
  bool was_reset_ = false;
};

}  // namespace upkie_rl
