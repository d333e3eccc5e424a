#pragma once
/// @file
/// Checkpoint files: one self-checking binary file holding a JSON header (configuration,
/// counters, random state, normalisation statistics, spaces) and float32 tensors (policy
/// weights, optimiser moments), closed by a CRC32C of everything before it. Written
/// atomically: a temporary file in the same directory, flushed, then renamed.
///
/// Layout: "UPKIERL1" | uint64 header size | header JSON | tensor bytes | uint32 CRC32C,
/// little-endian; the header lists each tensor's name and shape in storage order.

#include <torch/torch.h>

#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

namespace upkie_rl {

/// Raised for a missing, truncated, corrupted or inconsistent checkpoint.
class CheckpointError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The contents of a checkpoint.
struct Checkpoint {
  nlohmann::json header = nlohmann::json::object();  ///< Free-form metadata.
  std::map<std::string, torch::Tensor> tensors;      ///< float32 tensors by name.

  /// The tensor called `name`; throws CheckpointError naming it if absent or if its
  /// number of values differs from `numel` (when numel >= 0).
  const torch::Tensor& tensor(const std::string& name, std::int64_t numel = -1) const;
};

/// Writes `checkpoint` to `path` atomically (the file is either the old one or the new
/// one, never partial). Creates parent directories. Throws CheckpointError on I/O errors.
void save_checkpoint(const Checkpoint& checkpoint, const std::filesystem::path& path);

/// Reads and verifies a checkpoint. Throws CheckpointError naming the file and the
/// problem (not found, not a checkpoint, truncated, bad CRC, malformed header).
Checkpoint load_checkpoint(const std::filesystem::path& path);

}  // namespace upkie_rl
