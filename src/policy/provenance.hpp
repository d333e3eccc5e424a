#pragma once
/// @file
/// How a model was made: the upkie-rl version and commit that wrote it, when, from what
/// (training, or an import from another tool), the environment id and options, the training
/// configuration, the seed and the number of timesteps. Stored as the "provenance" entry of
/// a checkpoint header and carried by every export (TorchScript, ONNX, Stable-Baselines3).

#include <string>

#include <nlohmann/json.hpp>

namespace upkie_rl {

/// The value of a provenance field a model does not record (files older than provenance).
inline constexpr const char* kUnknownProvenance = "unknown";

/// The entry a writer puts in a header's "provenance": this build's version and commit, the
/// current UTC date (ISO 8601) and `source` (what made the model, e.g. "upkie-rl train").
nlohmann::json new_provenance(const std::string& source);

/// The complete provenance of a checkpoint header: its "provenance" entry (fields it lacks
/// read "unknown") completed from the rest of the header: env_id, env_options (object),
/// seed, timesteps and config (the training configuration, YAML text). Never throws on a
/// header without provenance: old models show "unknown".
nlohmann::json model_provenance(const nlohmann::json& header);

/// Human-readable lines of a provenance object, one "key: value" per field, the
/// configuration last and indented.
std::string format_provenance(const nlohmann::json& provenance);

}  // namespace upkie_rl
