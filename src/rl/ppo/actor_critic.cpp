#include "rl/ppo/actor_critic.hpp"

#include <cmath>
#include <cstring>
#include <stdexcept>

#include "policy/diagonal_gaussian.hpp"
#include "rl/ppo/tensor_activation.hpp"
#include "rl/ppo/tensor_span.hpp"

namespace upkie_rl {

std::int64_t count_parameters(std::int64_t observation_size, std::int64_t action_size,
                              const PolicyConfig& config) {
  return actor_critic_layout(observation_size, action_size, config.actor_hidden_sizes,
                             config.critic_hidden_sizes)
      .size;
}

void orthogonal_init(const torch::Tensor& tensor, double gain, at::Generator& generator) {
  torch::NoGradGuard no_grad;
  const std::int64_t rows = tensor.size(0);
  const std::int64_t columns = tensor.numel() / rows;
  torch::Tensor flattened = torch::randn({rows, columns}, generator, torch::kFloat32);
  if (rows < columns) flattened = flattened.t();
  auto [q, r] = torch::linalg_qr(flattened);
  q = q * torch::diagonal(r, 0).sign();
  if (rows < columns) q = q.t();
  tensor.view_as(q).copy_(q);
  tensor.mul_(gain);
}

ActorCritic::ActorCritic(std::int64_t observation_size, std::int64_t action_size,
                         const PolicyConfig& config, std::uint64_t seed)
    : observation_size_(observation_size), action_size_(action_size), config_(config) {
  if (observation_size < 1 || action_size < 1) {
    throw std::invalid_argument("ActorCritic: observation and action sizes must be positive");
  }
  const ActorCriticNetworks networks =
      actor_critic_networks(observation_size, action_size, config.actor_hidden_sizes,
                            config.critic_hidden_sizes, config.activation);
  actor_network_ = networks.actor;
  critic_network_ = networks.critic;
  flat_parameters_ = torch::zeros({networks.size}, torch::kFloat32);
  flat_gradients_ = torch::zeros({networks.size}, torch::kFloat32);
  actor_ = make_layers("actor", actor_network_);
  critic_ = make_layers("critic", critic_network_);
  log_std_ = make_parameter("log_std", {action_size}, networks.log_std);

  torch::NoGradGuard no_grad;
  at::Generator generator = at::make_generator<at::CPUGeneratorImpl>(seed);
  const double hidden_gain = std::sqrt(2.0);
  for (std::size_t i = 0; i < actor_.size(); ++i) {
    orthogonal_init(actor_[i].weight, i + 1 < actor_.size() ? hidden_gain : 0.01, generator);
  }
  for (std::size_t i = 0; i < critic_.size(); ++i) {
    orthogonal_init(critic_[i].weight, i + 1 < critic_.size() ? hidden_gain : 1.0, generator);
  }
  log_std_.fill_(config.log_std_init);
}

torch::Tensor ActorCritic::make_parameter(const std::string& name,
                                          const std::vector<std::int64_t>& shape,
                                          std::int64_t offset) {
  // A standalone leaf whose storage is moved into the flat buffers, so autograd
  // accumulates its gradient straight into flat_gradients_.
  std::int64_t numel = 1;
  for (std::int64_t size : shape) numel *= size;
  torch::Tensor parameter = register_parameter(name, torch::zeros(shape));
  parameter.set_data(flat_parameters_.narrow(0, offset, numel).view(shape));
  parameter.mutable_grad() = flat_gradients_.narrow(0, offset, numel).view(shape);
  return parameter;
}

std::vector<DenseLayer> ActorCritic::make_layers(const std::string& name, const Mlp& network) {
  std::vector<DenseLayer> layers;
  for (std::size_t i = 0; i < network.layers().size(); ++i) {
    const std::string prefix = name + "_" + std::to_string(i) + "_";
    const DenseLayerLayout& layer = network.layers()[i];
    layers.push_back({make_parameter(prefix + "weight", {layer.out, layer.in}, layer.weight),
                      make_parameter(prefix + "bias", {layer.out}, layer.bias)});
  }
  return layers;
}

// Mlp::forward's arithmetic on tensors, differentiable.
torch::Tensor ActorCritic::run_mlp(const Mlp& network, const std::vector<DenseLayer>& layers,
                                   torch::Tensor x) {
  for (std::size_t i = 0; i < layers.size(); ++i) {
    x = torch::addmm(layers[i].bias, x, layers[i].weight.t());
    if (network.activated(i)) x = activate(network.activation(), x);
  }
  return x;
}

torch::Tensor ActorCritic::action_mean(const torch::Tensor& observations) const {
  return run_mlp(actor_network_, actor_, observations);
}

torch::Tensor ActorCritic::value(const torch::Tensor& observations) const {
  return run_mlp(critic_network_, critic_, observations).view({-1});
}

ActionEvaluation ActorCritic::evaluate_actions(const torch::Tensor& observations,
                                               const torch::Tensor& actions) const {
  const torch::Tensor mean = action_mean(observations);
  // policy/diagonal_gaussian.hpp's formulas on tensors: log π = −½Σ z² − log_normaliser.
  const torch::Tensor z = (actions - mean) * torch::exp(-log_std_);
  ActionEvaluation out;
  out.log_prob = (z.square().sum(1)).mul(-0.5) -
                 (log_std_.sum() + kHalfLog2Pi * static_cast<double>(action_size_));
  out.entropy = (log_std_ + (0.5 + kHalfLog2Pi)).sum();
  out.values = value(observations);
  return out;
}

PolicyInference::PolicyInference(const ActorCritic& policy, std::int64_t batch_size)
    : policy_(policy), batch_size_(batch_size) {
  torch::NoGradGuard no_grad;
  input_ = torch::zeros({batch_size, policy.observation_size()});
  for (const DenseLayer& layer : policy.actor_layers()) {
    actor_weights_t_.push_back(layer.weight.t());
    actor_outputs_.push_back(torch::zeros({batch_size, layer.weight.size(0)}));
  }
  for (const DenseLayer& layer : policy.critic_layers()) {
    critic_weights_t_.push_back(layer.weight.t());
    critic_outputs_.push_back(torch::zeros({batch_size, layer.weight.size(0)}));
  }
}

void PolicyInference::forward(const Mlp& network, const std::vector<DenseLayer>& layers,
                              const std::vector<torch::Tensor>& weights_t,
                              std::vector<torch::Tensor>& outputs) {
  const torch::Tensor* x = &input_;
  for (std::size_t i = 0; i < layers.size(); ++i) {
    at::mm_out(outputs[i], *x, weights_t[i]);
    outputs[i].add_(layers[i].bias);
    if (network.activated(i)) activate_in_place(network.activation(), outputs[i]);
    x = &outputs[i];
  }
}

void PolicyInference::run_actor(std::span<const float> observations) {
  torch::NoGradGuard no_grad;
  if (static_cast<std::int64_t>(observations.size()) != input_.numel()) {
    throw std::invalid_argument("PolicyInference: expected " + std::to_string(input_.numel()) +
                                " observation values, got " + std::to_string(observations.size()));
  }
  std::memcpy(input_.data_ptr<float>(), observations.data(), observations.size_bytes());
  forward(policy_.actor_network(), policy_.actor_layers(), actor_weights_t_, actor_outputs_);
}

void PolicyInference::run_critic(std::span<const float> observations) {
  torch::NoGradGuard no_grad;
  if (static_cast<std::int64_t>(observations.size()) != input_.numel()) {
    throw std::invalid_argument("PolicyInference: expected " + std::to_string(input_.numel()) +
                                " observation values, got " + std::to_string(observations.size()));
  }
  std::memcpy(input_.data_ptr<float>(), observations.data(), observations.size_bytes());
  forward(policy_.critic_network(), policy_.critic_layers(), critic_weights_t_, critic_outputs_);
}

void PolicyInference::run(std::span<const float> observations) {
  run_actor(observations);
  torch::NoGradGuard no_grad;
  forward(policy_.critic_network(), policy_.critic_layers(), critic_weights_t_, critic_outputs_);
}

std::span<const float> PolicyInference::means() const {
  return tensor_values(actor_outputs_.back());
}

std::span<const float> PolicyInference::values() const {
  return tensor_values(critic_outputs_.back());
}

}  // namespace upkie_rl
