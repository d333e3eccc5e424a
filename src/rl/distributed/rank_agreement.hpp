#pragma once
/// @file
/// What the ranks of a data-parallel run must agree on, checked at the rendezvous before
/// any collective whose shapes depend on it: the resolved configuration (environment id
/// and options, num_envs, network, PPO settings, normalisation, seed) and the versions of
/// the checkpoint format and of libtorch. Ranks started with different settings would
/// otherwise abort inside an all-reduce or train different weights without a word.

#include <string>
#include <vector>

#include "rl/distributed/communicator.hpp"
#include "rl/runs/training_config.hpp"

namespace upkie_rl {

/// The settings that must match, as "key: value" lines (dotted keys).
std::vector<std::string> agreement_settings(const TrainingConfig& config);

/// Exchanges every rank's `settings` (one broadcast per rank) and, when any differs from
/// rank 0's, throws DistributedError on every rank with the same line naming the first
/// differing setting, the rank and both values. Does nothing alone.
void check_ranks_agree(const std::vector<std::string>& settings, Communicator& communicator);

}  // namespace upkie_rl
