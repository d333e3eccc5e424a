#pragma once
/// @file
/// The names an exported ONNX policy uses, written by onnx_export.cpp and read back by
/// onnx_model_info.cpp, the tests and users' deployment code.

#include "policy/checkpoint_header.hpp"
#include "policy/provenance.hpp"

namespace upkie_rl::onnx_names {

/// The graph's one input: raw observations, float32, shape (batch, observation size).
inline constexpr const char* kObservation = "observation";
/// The graph's one output: deterministic actions, float32, shape (batch, action size).
inline constexpr const char* kAction = "action";
/// The symbolic batch dimension of both.
inline constexpr const char* kBatch = "batch";

/// Metadata properties (ModelProto.metadata_props), named as the provenance's and the
/// checkpoint header's entries they copy. Spaces, options and provenance are JSON.
inline constexpr const char* kEnvId = provenance_key::kEnvId;
inline constexpr const char* kEnvOptions = provenance_key::kEnvOptions;
inline constexpr const char* kObservationSpace = checkpoint_header::kObservationSpace;
inline constexpr const char* kActionSpace = checkpoint_header::kActionSpace;
/// Control frequency in Hz (text), "unknown" when the environment does not say.
inline constexpr const char* kFrequency = "frequency";
inline constexpr const char* kProvenance = checkpoint_header::kProvenance;

}  // namespace upkie_rl::onnx_names
