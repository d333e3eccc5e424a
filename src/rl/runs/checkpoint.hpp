#pragma once
/// @file
/// Checkpoints with torch tensors: the trainer's view of a checkpoint file
/// (policy/checkpoint_file.hpp has the format, the checks and the errors).

#include <torch/torch.h>

#include <filesystem>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "policy/checkpoint_file.hpp"

namespace upkie_rl {

/// The contents of a checkpoint.
struct Checkpoint {
  nlohmann::json header = nlohmann::json::object();  ///< Free-form metadata.
  std::map<std::string, torch::Tensor> tensors;      ///< float32 tensors by name.

  /// The tensor called `name`; throws CheckpointError naming it if absent or if its
  /// number of values differs from `numel` (when numel >= 0).
  const torch::Tensor& tensor(const std::string& name, std::int64_t numel = -1) const;
};

/// Writes `checkpoint` to `path` atomically (see write_checkpoint_file).
void save_checkpoint(const Checkpoint& checkpoint, const std::filesystem::path& path);

/// Reads a checkpoint through the checkpoint gate (read_checked_checkpoint).
Checkpoint load_checkpoint(const std::filesystem::path& path);

}  // namespace upkie_rl
