#include "policy/mlp.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace upkie_rl {

namespace {

// `at_least`: a longer span is fine (the parameters of the other network, spare scratch).
void check_size(std::size_t size, std::size_t expected, const char* what, bool at_least) {
  if (at_least ? size < expected : size != expected) {
    throw std::invalid_argument(std::string("Mlp: ") + what + " has " + std::to_string(size) +
                                " values, expected " + (at_least ? "at least " : "") +
                                std::to_string(expected));
  }
}

}  // namespace

Mlp::Mlp(std::vector<DenseLayerLayout> layers, Activation activation)
    : layers_(std::move(layers)), activation_(activation) {
  if (layers_.empty()) throw std::invalid_argument("Mlp: no layers");
  for (const DenseLayerLayout& layer : layers_) {
    parameters_end_ = std::max(parameters_end_, layer.bias + layer.out);
  }
}

std::int64_t Mlp::input_size() const { return layers_.empty() ? 0 : layers_.front().in; }

std::int64_t Mlp::output_size() const { return layers_.empty() ? 0 : layers_.back().out; }

std::size_t Mlp::scratch_size() const {
  std::int64_t widest = 0;
  for (std::size_t l = 0; l < layers_.size(); ++l) {
    if (activated(l)) widest = std::max(widest, layers_[l].out);
  }
  return 2 * static_cast<std::size_t>(widest);
}

void Mlp::forward(std::span<const float> parameters, std::span<const float> input,
                  std::span<float> scratch, std::span<float> output) const {
  check_size(parameters.size(), static_cast<std::size_t>(parameters_end_), "parameters", true);
  check_size(input.size(), static_cast<std::size_t>(input_size()), "input", false);
  check_size(scratch.size(), scratch_size(), "scratch", true);
  check_size(output.size(), static_cast<std::size_t>(output_size()), "output", false);
  const std::size_t half = scratch.size() / 2;
  const float* x = input.data();
  for (std::size_t l = 0; l < layers_.size(); ++l) {
    const DenseLayerLayout& layer = layers_[l];
    float* y = activated(l) ? scratch.data() + (l % 2) * half : output.data();
    const float* weights = parameters.data() + layer.weight;
    const float* biases = parameters.data() + layer.bias;
    for (std::int64_t i = 0; i < layer.out; ++i) {
      double sum = biases[i];
      const float* w = weights + i * layer.in;
      for (std::int64_t j = 0; j < layer.in; ++j) sum += static_cast<double>(w[j]) * x[j];
      y[i] = static_cast<float>(activated(l) ? apply_activation(activation_, sum) : sum);
    }
    x = y;
  }
}

ActorCriticNetworks actor_critic_networks(std::int64_t observation_size, std::int64_t action_size,
                                          const std::vector<std::int64_t>& actor_hidden,
                                          const std::vector<std::int64_t>& critic_hidden,
                                          Activation activation) {
  const ActorCriticLayout layout =
      actor_critic_layout(observation_size, action_size, actor_hidden, critic_hidden);
  return {Mlp(layout.actor, activation), Mlp(layout.critic, activation), layout.log_std,
          layout.size};
}

}  // namespace upkie_rl
