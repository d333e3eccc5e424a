#pragma once
/// @file
/// The configuration of a training run, read from YAML (configs/pendulum.yaml,
/// configs/servos.yaml) with `key=value` overrides on dotted keys (`ppo.batch_size=64`).

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "base/option_table.hpp"
#include "policy/activation.hpp"
#include "vec/normalize_config.hpp"

namespace upkie_rl {

/// Largest timestep count of any setting (ppo.total_timesteps, checkpoint_every,
/// env.curriculum_steps): far beyond any run, far from int64 overflow.
inline constexpr std::int64_t kMaxTimesteps = 1'000'000'000'000'000;
/// Largest ppo.n_steps (the rollout buffer is also checked against the machine's memory).
inline constexpr std::int64_t kMaxRolloutSteps = std::int64_t{1} << 30;
/// Largest |ppo.clip_range_vf| and ppo.max_grad_norm: a finite float32 far beyond any
/// useful value (normalize.clip_* use vec/normalize_config.hpp's kMaxNormalizationClip).
inline constexpr double kMaxClip = 1e6;
/// Most intra-op threads of libtorch (torch_threads).
inline constexpr std::int64_t kMaxTorchThreads = 256;
/// Most threads of the hand-written gradient (ppo.update_threads): its work splits in two
/// independent parts, the actor's and the critic's.
inline constexpr std::int64_t kMaxUpdateThreads = 2;

/// Separate actor and critic MLPs (SB3 `net_arch=dict(pi=..., vf=...)`).
struct PolicyConfig {
  std::vector<std::int64_t> actor_hidden_sizes{64, 64};
  std::vector<std::int64_t> critic_hidden_sizes{64, 64};
  Activation activation = Activation::kReLU;
  double log_std_init = 0.0;  ///< Initial log standard deviation of the Gaussian.

  /// Declares the keys policy.* (training_config.cpp).
  void declare_options(OptionTable& table);
};

/// How Ppo::update computes the gradient of the loss (`ppo.gradient`; docs/training.md).
enum class GradientMethod {
  kAuto,      ///< hand when it covers the activation (relu, tanh), else autograd.
  kHand,      ///< The hand-written forward and backward pass (rl/ppo/ppo_gradient.hpp).
  kAutograd,  ///< libtorch's autograd (rl/ppo/autograd_ppo_gradient.hpp): every activation.
};

/// Steps each of `num_envs` environments collects per update of `n_steps` (all
/// environments together): n_steps / num_envs, at least 1. The rollout's length and the
/// bound of ppo.batch_size.
std::int64_t steps_per_env(std::int64_t n_steps, std::int64_t num_envs);

/// PPO hyperparameters with SB3 names and defaults of the seed.
struct PpoConfig {
  std::int64_t total_timesteps = 1'000'000;
  /// Steps per update, all environments together: each env collects n_steps / num_envs.
  std::int64_t n_steps = 2048;
  std::int64_t batch_size = 128;
  std::int64_t n_epochs = 5;
  double gamma = 0.99;
  double gae_lambda = 0.95;
  double clip_range = 0.2;
  double clip_range_vf = 0.2;  ///< Value clipping range; <= 0 disables value clipping.
  double ent_coef = 0.0;
  double vf_coef = 0.5;
  double max_grad_norm = 0.5;
  double learning_rate_initial = 2e-4;  ///< Linear schedule from this...
  double learning_rate_final = 1e-5;    ///< ...to this at the end of training.
  double adam_eps = 1e-5;
  bool normalize_advantage = true;
  GradientMethod gradient = GradientMethod::kAuto;  ///< Not SB3's: how the gradient is made.
  /// Not SB3's: threads of the hand-written gradient, 1 (the caller's) or 2 (with a
  /// companion running the critic's part beside the actor's). 2 by default: the results
  /// are the same bit for bit, sooner when a core is free. Unused by autograd.
  std::int64_t update_threads = 2;
  /// Not SB3's: trains on each sample and its left-right mirror image (the environment's
  /// Env::mirror_symmetry), which makes the policy mirror-symmetric
  /// (rl/ppo/mirrored_rollout.hpp). Each minibatch is twice ppo.batch_size.
  bool mirror_augmentation = false;

  /// Declares the keys ppo.*; n_steps and batch_size are checked against `num_envs`, the
  /// gradient against `activation` (both bound, read when the table checks).
  void declare_options(OptionTable& table, const std::int64_t& num_envs,
                       const Activation& activation);
};

/// Everything a training run needs.
struct TrainingConfig {
  std::string env_id = "Upkie-Bullet-Pendulum";
  /// Environment options as key=value strings, passed to the environment registry.
  std::vector<std::pair<std::string, std::string>> env_options;
  std::int64_t num_envs = 10;
  /// A second id of the same task on another engine (Upkie-Bullet-Velocity beside
  /// Upkie-MuJoCo-Velocity), stepped by mix_envs of the num_envs environments; "none"
  /// (with mix_envs 0) for none.
  std::string mix_env_id = "none";
  std::int64_t mix_envs = 0;
  /// Worker threads of the vector environment (0: synchronous stepping).
  std::int64_t env_threads = 2;
  /// Curriculum: every randomisation bound of the environments (initial state,
  /// perturbations, noise, lag, pushes) ramps linearly from 0 to its value over this many
  /// timesteps (0: full from the start). Env::set_randomization_scale.
  std::int64_t curriculum_steps = 0;
  /// Observation and reward normalisation (SB3 VecNormalize), keys normalize.*.
  NormalizeConfig normalize;
  PolicyConfig policy;
  PpoConfig ppo;
  std::uint64_t seed = 0;
  std::int64_t checkpoint_every = 50'000;  ///< Timesteps between checkpoints (0: none).
  /// Intra-op threads of libtorch. 1 by default: the networks are tiny, so threading costs
  /// more than it saves, and the cores are needed by the environment workers.
  std::int64_t torch_threads = 1;

  /// The curriculum's randomisation scale after `timesteps`: min(1, timesteps /
  /// curriculum_steps), or 1 without a curriculum.
  double randomization_scale(std::int64_t timesteps) const;

  /// Steps each environment collects per update: steps_per_env(ppo.n_steps, num_envs).
  std::int64_t steps_per_env() const;

  /// Declares every key (dotted, in YAML order) with its range, rules and help: the one
  /// list that parse_training_config, apply_overrides, validate and to_yaml read.
  /// env.options.* are the environment's (envs/registry/registry.hpp), not declared here.
  void declare_options(OptionTable& table);
  /// Declares env.id, env.num_envs, env.mix_id, env.mix_envs, env.threads and
  /// env.curriculum_steps.
  void declare_run_options(OptionTable& table);

  /// Throws std::invalid_argument naming the key of the first inconsistent or out-of-range
  /// value, its value and the range (one line). Every number must be finite, and every
  /// value must be one to_yaml can write back exactly.
  void validate() const;

  /// Throws std::invalid_argument naming the key when the network or the rollout buffer
  /// for these space sizes would be too large (policy/network_limits.hpp, and more than half
  /// of this machine's memory). Called before either is allocated.
  void check_allocations(std::int64_t observation_size, std::int64_t action_size) const;
};

/// Parses YAML text. Unknown keys, malformed values and missing sections raise
/// std::invalid_argument naming the dotted key. Keys absent from the text keep defaults.
TrainingConfig parse_training_config(const std::string& yaml_text);

/// Reads a YAML file (errors name the file and the key). A top-level `base: OTHER.yaml` (a path
/// relative to the file's directory) reads that configuration first, and this file's keys
/// over it: a key it sets replaces the base's, an env option is replaced or added one by one.
/// A chain of bases holds at most 8 files; a cycle is an error naming the base.
TrainingConfig load_training_config(const std::string& path);

/// Applies overrides "dotted.key=value" (`env.options.NAME=value` adds an env option).
/// Unknown keys and malformed values raise std::invalid_argument naming the key.
void apply_overrides(TrainingConfig& config, const std::vector<std::string>& overrides);

/// Whether `config` trains with the hand-written gradient (ppo.gradient hand, or auto and
/// an activation it covers) rather than autograd.
bool uses_hand_gradient(const TrainingConfig& config);

/// The full, resolved configuration as YAML, readable by parse_training_config, which
/// reads every value back exactly (text with control characters is written double-quoted,
/// with escapes). Throws std::invalid_argument naming the key of a value YAML cannot hold.
std::string to_yaml(const TrainingConfig& config);

}  // namespace upkie_rl
