#pragma once
/// @file
/// The diagonal Gaussian policy distribution N(μ, diag(σ²)) with a state-independent
/// log σ: the formulas of its log-probability and entropy, written once for the rollout
/// (rl/ppo/ppo.cpp), the hand-written gradient (rl/ppo/ppo_gradient.cpp) and autograd
/// (rl/ppo/actor_critic.cpp, which applies the same formulas to tensors).
///
///   log π(a|s) = −½ Σⱼ zⱼ² − log_normaliser,  zⱼ = (aⱼ − μⱼ) / σⱼ
///   log_normaliser = Σⱼ log σⱼ + ½·A·log 2π   (A: action components)
///   entropy = Σⱼ (log σⱼ + ½ + ½·log 2π)

#include <cstdint>
#include <span>

namespace upkie_rl {

/// ½·log(2π).
inline constexpr double kHalfLog2Pi = 0.91893853320467274178;

/// Σⱼ log σⱼ + ½·A·log 2π, summed in double in this order (½·A·log 2π first).
inline double gaussian_log_normaliser(std::span<const float> log_std) {
  double sum = kHalfLog2Pi * static_cast<double>(log_std.size());
  for (const float value : log_std) sum += value;
  return sum;
}

/// log π(a|s) = −½ Σⱼ zⱼ² − log_normaliser from Σⱼ zⱼ² and gaussian_log_normaliser.
inline double gaussian_log_probability(double squared_z_sum, double log_normaliser) {
  return -0.5 * squared_z_sum - log_normaliser;
}

/// Σⱼ (log σⱼ + ½ + ½·log 2π), in double.
inline double gaussian_entropy(std::span<const float> log_std) {
  double entropy = 0.0;
  for (const float value : log_std) entropy += value + 0.5 + kHalfLog2Pi;
  return entropy;
}

}  // namespace upkie_rl
