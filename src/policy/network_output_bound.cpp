#include "policy/network_output_bound.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "policy/checkpoint_file.hpp"

namespace upkie_rl {

namespace {

/// |f(y)| <= kActivationGain |y| + kActivationOffset for every activation (SELU's λ and λα
/// rounded up; ReLU, tanh, ELU, leaky ReLU, SiLU, GELU, sigmoid and softplus stay inside).
constexpr double kActivationGain = 1.0508;
constexpr double kActivationOffset = 1.7581;

std::string short_number(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3g", value);
  return text;
}

/// The largest-magnitude weight of `layer`: its index in the parameters.
std::int64_t largest_weight(std::span<const float> parameters, const DenseLayerLayout& layer) {
  std::int64_t largest = layer.weight;
  for (std::int64_t i = layer.weight; i < layer.bias + layer.out; ++i) {
    if (std::abs(parameters[i]) > std::abs(parameters[largest])) largest = i;
  }
  return largest;
}

}  // namespace

std::vector<double> network_input_bounds(const BoxSpace& observation_space,
                                         const ObservationNormalizer& normalizer) {
  std::vector<double> bounds(observation_space.size(), normalizer.clip());
  if (normalizer.enabled()) return bounds;
  for (std::size_t i = 0; i < bounds.size(); ++i) {
    const double magnitude = std::max(std::abs(static_cast<double>(observation_space.low[i])),
                                      std::abs(static_cast<double>(observation_space.high[i])));
    bounds[i] = std::min(magnitude, kMaxCheckedObservation);
  }
  return bounds;
}

double check_network_bound(std::span<const float> parameters,
                           const std::vector<DenseLayerLayout>& layers,
                           std::vector<double> input_bounds, const std::string& network) {
  double largest = 0.0;
  for (std::size_t l = 0; l < layers.size(); ++l) {
    const DenseLayerLayout& layer = layers[l];
    std::vector<double> output_bounds(static_cast<std::size_t>(layer.out));
    largest = 0.0;
    for (std::int64_t j = 0; j < layer.out; ++j) {
      double sum = std::abs(static_cast<double>(parameters[layer.bias + j]));
      const float* row = parameters.data() + layer.weight + j * layer.in;
      for (std::int64_t i = 0; i < layer.in; ++i) sum += std::abs(row[i]) * input_bounds[i];
      output_bounds[j] = sum;
      largest = std::max(largest, sum);
    }
    if (!(largest <= kMaxNetworkValue)) {
      const std::int64_t culprit = largest_weight(parameters, layer);
      throw CheckpointError(network + " layer " + std::to_string(l) + " can reach " +
                            short_number(largest) + " (limit " + short_number(kMaxNetworkValue) +
                            "): tensor 'policy.parameters' value " + std::to_string(culprit) +
                            " is " + short_number(parameters[culprit]));
    }
    if (l + 1 < layers.size()) {
      for (double& bound : output_bounds) bound = kActivationGain * bound + kActivationOffset;
    }
    input_bounds = std::move(output_bounds);
  }
  return largest;
}

void check_log_std(std::span<const float> parameters, std::int64_t offset, std::int64_t count) {
  for (std::int64_t i = offset; i < offset + count; ++i) {
    if (!(std::abs(parameters[i]) <= kMaxLogStd)) {
      throw CheckpointError("log std " + std::to_string(i - offset) +
                            " (tensor 'policy.parameters' value " + std::to_string(i) + ") is " +
                            short_number(parameters[i]) + ", outside [" +
                            short_number(-kMaxLogStd) + ", " + short_number(kMaxLogStd) + "]");
    }
  }
}

}  // namespace upkie_rl
