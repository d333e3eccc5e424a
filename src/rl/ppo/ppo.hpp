#pragma once
/// @file
/// Proximal Policy Optimisation with SB3 semantics on a VectorEnv: rollout collection with
/// truncation bootstrapping, GAE, and clipped updates of an ActorCritic with FlatAdam.

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "rl/distributed/communicator.hpp"
#include "rl/logging/episode_statistics.hpp"
#include "rl/logging/reward_term_statistics.hpp"
#include "rl/ppo/actor_critic.hpp"
#include "rl/ppo/flat_adam.hpp"
#include "rl/ppo/linear_schedule.hpp"
#include "rl/ppo/mirrored_rollout.hpp"
#include "rl/ppo/ppo_gradient.hpp"
#include "rl/ppo/rollout_buffer.hpp"
#include "rl/runs/training_config.hpp"
#include "vec/vector_env.hpp"

namespace upkie_rl {

/// What one update logs (SB3 `train/*` names in comments).
struct PpoUpdateStatistics {
  double loss = 0.0;                  ///< train/loss (last minibatch).
  double policy_gradient_loss = 0.0;  ///< train/policy_gradient_loss (mean of minibatches).
  double value_loss = 0.0;            ///< train/value_loss.
  double entropy_loss = 0.0;          ///< train/entropy_loss.
  double approx_kl = 0.0;             ///< train/approx_kl.
  double clip_fraction = 0.0;         ///< train/clip_fraction.
  double explained_variance = 0.0;    ///< train/explained_variance.
  double learning_rate = 0.0;         ///< train/learning_rate.
  double std = 0.0;                   ///< train/std: mean of σ.
  double clip_range = 0.0;            ///< train/clip_range.
  std::int64_t n_updates = 0;         ///< train/n_updates: epochs so far.
};

/// Wall time spent in each part of training, in seconds.
struct PpoTimings {
  double env_seconds = 0.0;        ///< Inside VectorEnv::step and reset.
  double inference_seconds = 0.0;  ///< Policy forward passes and sampling in rollouts.
  double update_seconds = 0.0;     ///< GAE and gradient updates.
  /// Of those, waiting for and summing over the other ranks (DD-PPO's all-reduces).
  double communication_seconds = 0.0;
};

/// The PPO learner. It does not own the environment; the caller keeps it alive.
class Ppo {
 public:
  /// Builds the policy (initialised from config.seed) and optimiser for `env`'s spaces.
  /// Throws std::invalid_argument if the config does not fit the environment.
  Ppo(VectorEnv& env, const TrainingConfig& config);

  /// Resets every environment (env i with seed + i) and starts new episodes.
  void reset_environments(std::uint64_t seed);

  /// Collects steps_per_env() x num_envs transitions with the stochastic policy, then
  /// computes advantages and returns. Requires reset_environments() first.
  void collect_rollout();

  /// Called after every vector step of collect_rollout() with the step and the (clipped)
  /// actions that made it; for viewers. Empty by default.
  using StepObserver = std::function<void(const VectorStep& step, std::span<const float> actions)>;
  void set_step_observer(StepObserver observer) { step_observer_ = std::move(observer); }

  /// Makes this learner one rank of a data-parallel run (DD-PPO): every rank steps its own
  /// environments; the gradient of each minibatch is averaged over the ranks before the
  /// optimiser step, so the weights stay identical (rank 0's are broadcast here first);
  /// ended episodes are gathered from every rank; timesteps count every rank's steps.
  /// Ranks other than 0 draw their actions and minibatches from generators of their own.
  /// The communicator must outlive the learner. Call before the first rollout.
  void set_communicator(Communicator* communicator);

  /// On ranks other than 0, restarts the generator of action noise and minibatches from
  /// (seed, rank, `segment`); rank 0's generator is left as it is (checkpoints save it).
  /// Called at every checkpoint, so that a data-parallel run resumed from one with the same
  /// world size draws on every rank what the uninterrupted run drew.
  void reseed_rank_stream(std::uint64_t segment);

  /// Sets the learning rate from the progress so far and runs n_epochs over the rollout.
  PpoUpdateStatistics update();

  /// One iteration: collect_rollout() then update().
  PpoUpdateStatistics iterate();

  std::int64_t num_timesteps() const { return num_timesteps_; }
  /// Whether update() uses the hand-written gradient (else autograd): uses_hand_gradient.
  bool uses_hand_gradient() const { return gradient_.has_value(); }
  /// Threads the hand-written gradient runs on (ppo.update_threads); 1 with autograd.
  std::int64_t update_threads() const { return gradient_ ? gradient_->update_threads() : 1; }
  std::int64_t iterations() const { return iterations_; }
  std::int64_t n_updates() const { return n_updates_; }
  const TrainingConfig& config() const { return config_; }
  const VectorEnv& env() const { return env_; }
  ActorCritic& policy() { return *policy_; }
  const ActorCritic& policy() const { return *policy_; }
  FlatAdam& optimizer() { return optimizer_; }
  const FlatAdam& optimizer() const { return optimizer_; }
  const EpisodeStatistics& episodes() const { return episodes_; }
  /// Each reward term's episode sum over the last episodes of this rank's environments
  /// (VectorEnv::reward_term_names(); not gathered over DD-PPO ranks).
  const RewardTermStatistics& reward_terms() const { return reward_terms_; }
  const PpoTimings& timings() const { return timings_; }
  const RolloutBuffer& buffer() const { return buffer_; }
  /// The learning rate the schedule gives after `timesteps`.
  double learning_rate_at(std::int64_t timesteps) const;

  /// Counters and random state for checkpoints (the weights and optimiser moments are
  /// saved from policy() and optimizer()).
  nlohmann::json counters_state() const;
  /// Restores counters_state(); throws std::invalid_argument on a malformed state.
  void load_counters_state(const nlohmann::json& state);

 private:
  /// One step of a rollout before the environments step: the policy's means and values of
  /// the last observations, the sampled actions (into the buffer's row `t`, clipped into
  /// clipped_actions_) and their log-probabilities.
  void sample_actions(std::int64_t t, std::span<const double> stds, double log_normaliser);
  /// The environments' step `step` into the buffer's row `t`: rewards (bootstrapped at time
  /// limits), dones, and the episodes that ended.
  void record_step(std::int64_t t, const VectorStep& step);
  VectorEnv& env_;
  TrainingConfig config_;
  std::int64_t observation_size_;
  std::int64_t action_size_;
  std::int64_t num_envs_;
  std::unique_ptr<ActorCritic> policy_;
  FlatAdam optimizer_;
  LinearSchedule learning_rate_;
  RolloutBuffer buffer_;
  PolicyInference inference_;
  /// Loss and gradient of a minibatch, buffers sized once; empty when the config trains
  /// with autograd (uses_hand_gradient).
  std::optional<PpoGradient> gradient_;
  /// The images of the rollout's samples, with ppo.mirror_augmentation; empty otherwise.
  std::optional<MirroredRollout> mirrored_;
  EpisodeStatistics episodes_;
  RewardTermStatistics reward_terms_;
  PpoTimings timings_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_;
  StepObserver step_observer_;
  SoloCommunicator solo_;
  Communicator* communicator_ = &solo_;
  /// Episodes ended in this rollout (return, length), gathered over the ranks at its end.
  std::vector<double> ended_episodes_;
  void gather_ended_episodes();
  /// Communicator::average of a tensor or a span of doubles, timed.
  template <typename Values>
  void average_over_ranks(Values values);
  bool started_ = false;
  std::int64_t num_timesteps_ = 0;
  std::int64_t iterations_ = 0;
  std::int64_t n_updates_ = 0;
  // Rollout scratch, sized once.
  std::vector<float> last_observations_;
  std::vector<float> clipped_actions_;
  std::vector<float> last_values_;
  std::vector<float> action_low_;
  std::vector<float> action_high_;
  std::vector<std::int64_t> permutation_;
};

}  // namespace upkie_rl
