#pragma once
/// @file
/// The checkpoint gate's proof that a network's values stay finite: interval bound
/// propagation over the stored weights. For inputs with |x_i| <= bound_i, each dense layer's
/// outputs satisfy |y_j| <= sum_i |W_ji| bound_i + |b_j|, and every activation of
/// policy/activation.hpp keeps |f(y)| <= 1.0508 |y| + 1.7581 (SELU's scale λ and λα; the
/// others stay inside). A network whose bound stays below kMaxNetworkValue at every layer
/// can neither overflow float32 nor make a NaN for any such input, whatever the weights'
/// pattern; the gate refuses the others. The bound costs one pass over the weights, at load.
///
/// The inputs are the normalised observations, within ±clip_observations, or the raw ones
/// when the policy does not normalise: within the observation space's bounds, at most
/// kMaxCheckedObservation (a component the space leaves unbounded included). An
/// observation beyond that is caught at run time (DeployedPolicy::act refuses a non-finite
/// action with PolicyOutputError).

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "envs/spaces/box_space.hpp"
#include "policy/observation_normalizer.hpp"
#include "policy/parameter_layout.hpp"

namespace upkie_rl {

/// Largest magnitude a layer of the actor or critic may reach for an input in range: 1e30,
/// far inside float32's 3.4e38 (so that no sum overflows), far beyond trained policies
/// (the bounds of the checked-in policies, tests/data/policies, are 284 to 3,461).
inline constexpr double kMaxNetworkValue = 1e30;
/// Largest magnitude of a raw observation component the bound covers (positions in m,
/// angles in rad, velocities in m/s or rad/s: no measurement comes near).
inline constexpr double kMaxCheckedObservation = 1e6;
/// Range of the policy's log standard deviations, [-kMaxLogStd, kMaxLogStd]: σ from 2e-9
/// to 5e8, which training's sampling and log-probabilities hold in float32
/// (policy.log_std_init is in [-20, 5]).
inline constexpr double kMaxLogStd = 20.0;

/// The magnitude bound of each input component the networks see (see the file comment).
std::vector<double> network_input_bounds(const BoxSpace& observation_space,
                                         const ObservationNormalizer& normalizer);

/// The largest magnitude of the output of `layers` (in `parameters`, the checkpoint's
/// "policy.parameters") over inputs within `input_bounds`. Throws CheckpointError naming
/// `network`, the layer, its bound and its largest weight (value and index in
/// policy.parameters) when a layer's bound passes kMaxNetworkValue.
double check_network_bound(std::span<const float> parameters,
                           const std::vector<DenseLayerLayout>& layers,
                           std::vector<double> input_bounds, const std::string& network);

/// Throws CheckpointError naming the index of the first of the `count` log σ at `offset`
/// of `parameters` outside [-kMaxLogStd, kMaxLogStd].
void check_log_std(std::span<const float> parameters, std::int64_t offset, std::int64_t count);

}  // namespace upkie_rl
