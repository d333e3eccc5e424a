#pragma once
/// @file
/// The PPO policy: separate actor and critic MLPs and a state-independent log standard
/// deviation, a diagonal Gaussian over actions (SB3 ActorCriticPolicy with ortho_init).

#include <torch/torch.h>

#include <cstdint>
#include <span>
#include <vector>

#include "policy/mlp.hpp"
#include "rl/runs/training_config.hpp"

namespace upkie_rl {

/// One fully-connected layer: y = x·Wᵀ + b.
struct DenseLayer {
  torch::Tensor weight;  ///< out x in.
  torch::Tensor bias;    ///< out.
};

/// Log-probabilities, entropy and values of a batch under the current policy.
struct ActionEvaluation {
  torch::Tensor log_prob;  ///< batch: log π(a|s), summed over action components.
  torch::Tensor entropy;   ///< scalar: entropy of the Gaussian (the same for every state).
  torch::Tensor values;    ///< batch: V(s).
};

/// Actor-critic MLPs whose parameters all live in one flat float32 buffer (and their
/// gradients in another), so that the optimiser and gradient clipping are a few tensor
/// operations on the whole set rather than a few per parameter.
class ActorCritic final : public torch::nn::Module {
 public:
  /// Builds the networks with orthogonal initialisation (gain √2 for hidden layers, 0.01
  /// for the action head, 1 for the value head, zero biases) drawn from `seed`.
  ActorCritic(std::int64_t observation_size, std::int64_t action_size, const PolicyConfig& config,
              std::uint64_t seed);

  std::int64_t observation_size() const { return observation_size_; }
  std::int64_t action_size() const { return action_size_; }
  const PolicyConfig& config() const { return config_; }

  /// The actor's description (layers in flat_parameters(), where the activation goes),
  /// shared with deployment and export: actor_layers() are its layers as tensors.
  const Mlp& actor_network() const { return actor_network_; }
  /// The critic's description, as actor_network().
  const Mlp& critic_network() const { return critic_network_; }
  /// Hidden layers then the action head (last).
  const std::vector<DenseLayer>& actor_layers() const { return actor_; }
  /// Hidden layers then the value head (last, one output).
  const std::vector<DenseLayer>& critic_layers() const { return critic_; }
  /// Log standard deviation of each action component.
  const torch::Tensor& log_std() const { return log_std_; }

  /// Every parameter, concatenated (actor, critic, log σ: policy/parameter_layout.hpp).
  /// Writing it changes the model.
  torch::Tensor& flat_parameters() { return flat_parameters_; }
  const torch::Tensor& flat_parameters() const { return flat_parameters_; }
  /// The gradients of flat_parameters(), accumulated by backward().
  torch::Tensor& flat_gradients() { return flat_gradients_; }

  /// Zeroes the gradients in place (they stay views of flat_gradients()).
  void zero_gradients() { flat_gradients_.zero_(); }

  /// Mean action μ(s) for a batch of (normalised) observations, differentiable.
  torch::Tensor action_mean(const torch::Tensor& observations) const;
  /// V(s) for a batch of observations (shape batch), differentiable.
  torch::Tensor value(const torch::Tensor& observations) const;

  /// log π(actions|observations), entropy and V(observations), differentiable.
  ActionEvaluation evaluate_actions(const torch::Tensor& observations,
                                    const torch::Tensor& actions) const;

 private:
  torch::Tensor make_parameter(const std::string& name, const std::vector<std::int64_t>& shape,
                               std::int64_t offset);
  std::vector<DenseLayer> make_layers(const std::string& name, const Mlp& network);
  static torch::Tensor run_mlp(const Mlp& network, const std::vector<DenseLayer>& layers,
                               torch::Tensor x);

  std::int64_t observation_size_;
  std::int64_t action_size_;
  PolicyConfig config_;
  Mlp actor_network_;
  Mlp critic_network_;
  torch::Tensor flat_parameters_;
  torch::Tensor flat_gradients_;
  std::vector<DenseLayer> actor_;
  std::vector<DenseLayer> critic_;
  torch::Tensor log_std_;
};

/// Number of float parameters of an actor-critic with these sizes.
std::int64_t count_parameters(std::int64_t observation_size, std::int64_t action_size,
                              const PolicyConfig& config);

/// Fills `tensor` (2-D) with a (semi-)orthogonal matrix times `gain`, like
/// torch.nn.init.orthogonal_, drawing from `generator`.
void orthogonal_init(const torch::Tensor& tensor, double gain, at::Generator& generator);

/// Runs the actor and critic on a fixed batch of observations without autograd and
/// without allocating: every intermediate tensor is made once, in the constructor. This is
/// the rollout hot path. It follows the networks' Mlp description but multiplies with
/// torch's batched float32 matmul rather than Mlp::forward's per-input double sums: the
/// rollout's actions, hence the trained weights, are those of torch's arithmetic, and a
/// batch of environments runs as one matrix product.
class PolicyInference {
 public:
  /// `batch_size` rows of observations per call. Keeps a reference to `policy`, whose
  /// parameter updates it sees.
  PolicyInference(const ActorCritic& policy, std::int64_t batch_size);

  /// Computes μ and V for `observations` (batch_size x observation_size, normalised).
  void run(std::span<const float> observations);
  /// Computes μ only.
  void run_actor(std::span<const float> observations);
  /// Computes V only.
  void run_critic(std::span<const float> observations);

  /// batch_size x action_size means of the last run.
  std::span<const float> means() const;
  /// batch_size values of the last run.
  std::span<const float> values() const;

 private:
  void forward(const Mlp& network, const std::vector<DenseLayer>& layers,
               const std::vector<torch::Tensor>& weights_t, std::vector<torch::Tensor>& outputs);

  const ActorCritic& policy_;
  std::int64_t batch_size_;
  torch::Tensor input_;
  std::vector<torch::Tensor> actor_weights_t_;
  std::vector<torch::Tensor> critic_weights_t_;
  std::vector<torch::Tensor> actor_outputs_;
  std::vector<torch::Tensor> critic_outputs_;
};

}  // namespace upkie_rl
