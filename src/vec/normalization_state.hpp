#pragma once
/// @file
/// The keys of the normalisation state (VecNormalize::state(), a checkpoint header's
/// "normalization" entry), declared once for its writer (vec/vec_normalize.cpp,
/// vec/running_mean_std.cpp), its readers (VecNormalize::load_state,
/// policy/observation_normalizer.cpp), the training configuration's normalize.* options,
/// which carry the same names, and Python (_core.normalization_state_keys(), with which
/// upkie_rl/sb3_convert.py converts Stable-Baselines3's VecNormalize files both ways).
/// The wire text is the one of every checkpoint written so far.

#include "base/named_key.hpp"

namespace upkie_rl::normalization_state {

// The one list: X(constant, wire text), as in policy/checkpoint_header.hpp.
// - kObservationStatistics, kReturnStatistics: the running statistics
//   (RunningMeanStd::to_json), each {kMean: [...], kVar: [...], kCount: number}.
// - kConfig: the NormalizeConfig, kObservations to kEpsilon; kObservations and kRewards
//   say whether each is normalised (the same text as the statistics' kObservationStatistics,
//   one level down).
// NOLINTBEGIN(cppcoreguidelines-macro-usage): an X-macro, the one way to declare each key
// once for both its constant and the table.
#define UPKIE_RL_NORMALIZATION_STATE_KEYS(X) \
  X(kObservationStatistics, "observations")  \
  X(kReturnStatistics, "returns")            \
  X(kMean, "mean")                           \
  X(kVar, "var")                             \
  X(kCount, "count")                         \
  X(kConfig, "config")                       \
  X(kObservations, "observations")           \
  X(kRewards, "rewards")                     \
  X(kClipObservations, "clip_observations")  \
  X(kClipRewards, "clip_rewards")            \
  X(kGamma, "gamma")                         \
  X(kEpsilon, "epsilon")

UPKIE_RL_NORMALIZATION_STATE_KEYS(UPKIE_RL_NAMED_KEY_CONSTANT)

/// Every key, in the order of the list.
inline constexpr NamedKey kAllKeys[] = {
    UPKIE_RL_NORMALIZATION_STATE_KEYS(UPKIE_RL_NAMED_KEY_ENTRY)};
// NOLINTEND(cppcoreguidelines-macro-usage)

}  // namespace upkie_rl::normalization_state
