#pragma once
/// @file
/// The keys of a checkpoint's JSON header (policy/checkpoint_file.hpp), declared once for
/// its writers (rl/runs/ppo_checkpoint.cpp, rl/runs/training_run.cpp, the SB3 import) and readers
/// (policy/checkpoint_gate.cpp, policy/deployed_policy.cpp, policy/provenance.cpp, the
/// trainer's resume), for the exports that copy entries of it (TorchScript, ONNX), and for
/// Python (_core.checkpoint_header_keys(), which upkie_rl/sb3_convert.py reads).
/// The wire text is the one of every checkpoint written so far: these are its names.

#include "base/named_key.hpp"

namespace upkie_rl::checkpoint_header {

// The one list: X(constant, wire text). It defines the constants below and the table of
// kAllKeys, so that a key added here reaches C++ and Python (a list rather than separate
// constants, because a separate table for the bindings could miss one).
// - kFormat, kVersion: kCheckpointFormat (policy/model_header.hpp), kCheckpointVersion
//   (policy/checkpoint_gate.hpp).
// - kConfig: the resolved training configuration, YAML text.
// - kPolicy: the actor-critic's PolicyShape (policy/model_header.hpp), whose entries are
//   kObservationSize to kActivation.
// - kObservationSpace, kActionSpace: the environment's spaces (policy/space_json.hpp).
// - kNormalization: the VecNormalize state, null without normalisation.
// - kCounters: the trainer's counters (Ppo::counters_state): kNumTimesteps to kEpisodes
//   (the random generators' state as text, the recent episodes' statistics).
// - kOptimizer: the optimizer's state besides its moment tensors: {kStepCount: integer}.
// - kRun: the training run's state: {kCheckpointsSaved: integer}.
// - kProvenance: where the model comes from (policy/provenance.hpp).
// - kPolicyParameters, kOptimizerExpAvg, kOptimizerExpAvgSq: names of the checkpoint's
//   tensors: the actor-critic's parameters in the order of policy/parameter_layout.hpp,
//   and Adam's moments of the same length.
// NOLINTBEGIN(cppcoreguidelines-macro-usage): an X-macro, the one way to declare each key
// once for both its constant and the table.
#define UPKIE_RL_CHECKPOINT_HEADER_KEYS(X)     \
  X(kFormat, "format")                         \
  X(kVersion, "version")                       \
  X(kConfig, "config")                         \
  X(kPolicy, "policy")                         \
  X(kObservationSize, "observation_size")      \
  X(kActionSize, "action_size")                \
  X(kActorHiddenSizes, "actor_hidden_sizes")   \
  X(kCriticHiddenSizes, "critic_hidden_sizes") \
  X(kActivation, "activation")                 \
  X(kObservationSpace, "observation_space")    \
  X(kActionSpace, "action_space")              \
  X(kNormalization, "normalization")           \
  X(kCounters, "counters")                     \
  X(kNumTimesteps, "num_timesteps")            \
  X(kIterations, "iterations")                 \
  X(kNUpdates, "n_updates")                    \
  X(kRandomState, "random_state")              \
  X(kEpisodes, "episodes")                     \
  X(kOptimizer, "optimizer")                   \
  X(kStepCount, "step_count")                  \
  X(kRun, "run")                               \
  X(kCheckpointsSaved, "checkpoints_saved")    \
  X(kProvenance, "provenance")                 \
  X(kPolicyParameters, "policy.parameters")    \
  X(kOptimizerExpAvg, "optimizer.exp_avg")     \
  X(kOptimizerExpAvgSq, "optimizer.exp_avg_sq")

UPKIE_RL_CHECKPOINT_HEADER_KEYS(UPKIE_RL_NAMED_KEY_CONSTANT)

/// Every key, in the order of the list.
inline constexpr NamedKey kAllKeys[] = {UPKIE_RL_CHECKPOINT_HEADER_KEYS(UPKIE_RL_NAMED_KEY_ENTRY)};
// NOLINTEND(cppcoreguidelines-macro-usage)

}  // namespace upkie_rl::checkpoint_header
