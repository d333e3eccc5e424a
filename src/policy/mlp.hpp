#pragma once
/// @file
/// The one description of the policy's networks: a multilayer perceptron whose parameters
/// lie in a flat float32 buffer (policy/parameter_layout.hpp), dense layers y = x·Wᵀ + b
/// with the activation after every layer but the last (the output layer).
///
/// Everything that runs or writes a network reads this description: DeployedPolicy runs
/// forward() (deployment, `rollout --model`, the robot runner, Python); the ONNX and
/// TorchScript exporters walk layers() and activated(); the trainer's torch forward passes
/// (rl/ppo/actor_critic.hpp: autograd, and the rollout's batched inference) and its hand-written
/// gradient (rl/ppo/ppo_gradient.hpp) build their layers from it and ask activated() where the
/// activation goes.

#include <cstdint>
#include <span>
#include <vector>

#include "policy/activation.hpp"
#include "policy/parameter_layout.hpp"

namespace upkie_rl {

/// Dense layers in a flat parameter buffer with an activation between them.
class Mlp {
 public:
  Mlp() = default;
  /// `layers`: hidden layers then the output layer, each layer's input the previous output.
  Mlp(std::vector<DenseLayerLayout> layers, Activation activation);

  /// Hidden layers, then the output layer.
  const std::vector<DenseLayerLayout>& layers() const { return layers_; }
  Activation activation() const { return activation_; }
  /// Whether layer `index`'s output goes through the activation: every layer's but the
  /// output layer's.
  bool activated(std::size_t index) const { return index + 1 < layers_.size(); }
  std::int64_t input_size() const;
  std::int64_t output_size() const;
  /// Floats of scratch forward() needs: two buffers as wide as the widest hidden layer.
  std::size_t scratch_size() const;

  /// output = MLP(input) for one input, in the flat `parameters` the layers index. Sums
  /// each product in double, so that the result agrees with torch's float32 matmul to
  /// about 1e-6 whatever the summation order. Allocation-free.
  /// @throws std::invalid_argument on spans of the wrong size.
  void forward(std::span<const float> parameters, std::span<const float> input,
               std::span<float> scratch, std::span<float> output) const;

 private:
  std::vector<DenseLayerLayout> layers_;
  Activation activation_ = Activation::kReLU;
  std::int64_t parameters_end_ = 0;  // One past the last parameter the layers use.
};

/// The actor-critic's two networks in its flat buffer: actor_critic_layout with the
/// activation.
struct ActorCriticNetworks {
  Mlp actor;                 ///< Output size action_size: the Gaussian's mean.
  Mlp critic;                ///< Output size 1: the value.
  std::int64_t log_std = 0;  ///< Offset of the action_size log σ.
  std::int64_t size = 0;     ///< Number of parameters.
};

ActorCriticNetworks actor_critic_networks(std::int64_t observation_size, std::int64_t action_size,
                                          const std::vector<std::int64_t>& actor_hidden,
                                          const std::vector<std::int64_t>& critic_hidden,
                                          Activation activation);

}  // namespace upkie_rl
