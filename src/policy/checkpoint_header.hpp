#pragma once
/// @file
/// The keys of a checkpoint's JSON header (policy/checkpoint_file.hpp), declared once for
/// its writers (rl/ppo_checkpoint.cpp, rl/training_run.cpp, the SB3 import) and readers
/// (policy/checkpoint_gate.cpp, policy/deployed_policy.cpp, policy/provenance.cpp, the
/// trainer's resume), and for the exports that copy entries of it (TorchScript, ONNX).
/// The wire text is the one of every checkpoint written so far: these are its names.

namespace upkie_rl::checkpoint_header {

/// kCheckpointFormat (policy/model_header.hpp).
inline constexpr const char* kFormat = "format";
/// kCheckpointVersion (policy/checkpoint_gate.hpp).
inline constexpr const char* kVersion = "version";
/// The resolved training configuration, YAML text.
inline constexpr const char* kConfig = "config";
/// The actor-critic's PolicyShape (policy/model_header.hpp).
inline constexpr const char* kPolicy = "policy";
/// The environment's spaces (policy/space_json.hpp).
inline constexpr const char* kObservationSpace = "observation_space";
inline constexpr const char* kActionSpace = "action_space";
/// The VecNormalize state, null without normalisation.
inline constexpr const char* kNormalization = "normalization";
/// The trainer's counters (Ppo::counters_state), with the entries below.
inline constexpr const char* kCounters = "counters";
inline constexpr const char* kNumTimesteps = "num_timesteps";
inline constexpr const char* kIterations = "iterations";
inline constexpr const char* kNUpdates = "n_updates";
/// The optimizer's state besides its moment tensors: {kStepCount: integer}.
inline constexpr const char* kOptimizer = "optimizer";
inline constexpr const char* kStepCount = "step_count";
/// The training run's state: {kCheckpointsSaved: integer}.
inline constexpr const char* kRun = "run";
inline constexpr const char* kCheckpointsSaved = "checkpoints_saved";
/// Where the model comes from (policy/provenance.hpp).
inline constexpr const char* kProvenance = "provenance";

/// Names of the checkpoint's tensors: the actor-critic's parameters in the order of
/// policy/parameter_layout.hpp, and Adam's moments of the same length.
inline constexpr const char* kPolicyParameters = "policy.parameters";
inline constexpr const char* kOptimizerExpAvg = "optimizer.exp_avg";
inline constexpr const char* kOptimizerExpAvgSq = "optimizer.exp_avg_sq";

}  // namespace upkie_rl::checkpoint_header
