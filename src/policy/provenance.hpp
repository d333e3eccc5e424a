#pragma once
/// @file
/// How a model was made: the upkie-rl version and commit that wrote it, when, from what
/// (training, or an import from another tool), the environment id and options, the training
/// configuration, the seed and the number of timesteps. Stored as the "provenance" entry of
/// a checkpoint header and carried by every export (TorchScript, ONNX, Stable-Baselines3).

#include <string>

#include <nlohmann/json.hpp>

#include "base/named_key.hpp"

namespace upkie_rl {

namespace provenance_key {

// The one list of a provenance object's keys: X(constant, wire text, always), as in
// policy/checkpoint_header.hpp. `always`: model_provenance gives the key to every model,
// "unknown" when it cannot say; the others are only there when their writer put them:
// kImportedFrom ({kFile, kSha256, kStableBaselines3Version}) and kOriginal (the provenance
// of the model an SB3 zip was exported from) are written by the SB3 import
// (upkie_rl/sb3_convert.py, through _core.provenance_keys()).
// NOLINTBEGIN(cppcoreguidelines-macro-usage): an X-macro, the one way to declare each key
// once for its constant, the table and the list of keys every model has.
#define UPKIE_RL_PROVENANCE_KEYS(X)                               \
  X(kUpkieRlVersion, "upkie_rl_version", true)                    \
  X(kGitCommit, "git_commit", true)                               \
  X(kDate, "date", true)                                          \
  X(kSource, "source", true)                                      \
  X(kEnvId, "env_id", true)                                       \
  X(kEnvOptions, "env_options", true)                             \
  X(kSeed, "seed", true)                                          \
  X(kTimesteps, "timesteps", true)                                \
  X(kConfig, "config", true)                                      \
  X(kImportedFrom, "imported_from", false)                        \
  X(kFile, "file", false)                                         \
  X(kSha256, "sha256", false)                                     \
  X(kStableBaselines3Version, "stable_baselines3_version", false) \
  X(kOriginal, "original", false)

UPKIE_RL_PROVENANCE_KEYS(UPKIE_RL_NAMED_KEY_CONSTANT)

/// Every key, in the order of the list.
inline constexpr NamedKey kAllKeys[] = {UPKIE_RL_PROVENANCE_KEYS(UPKIE_RL_NAMED_KEY_ENTRY)};

#define UPKIE_RL_PROVENANCE_ALWAYS(name, text, always) always,
/// Whether each key of kAllKeys is one every model's provenance has.
inline constexpr bool kAlways[] = {UPKIE_RL_PROVENANCE_KEYS(UPKIE_RL_PROVENANCE_ALWAYS)};
#undef UPKIE_RL_PROVENANCE_ALWAYS
// NOLINTEND(cppcoreguidelines-macro-usage)

}  // namespace provenance_key

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
