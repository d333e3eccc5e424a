#pragma once
/// @file
/// Checkpoint files, without libtorch: one self-checking binary file holding a JSON header
/// (configuration, counters, random state, normalisation statistics, spaces) and named
/// float32 tensors (policy weights, optimiser moments), closed by a CRC32C of everything
/// before it. Written atomically: a temporary file in the same directory, flushed, then
/// renamed. rl/runs/checkpoint.hpp converts the tensors to and from torch.
///
/// Layout: "UPKIERL1" | uint64 header size | header JSON | tensor bytes | uint32 CRC32C,
/// little-endian; the header's "tensors" array lists each tensor's name and shape in
/// storage order (the readers remove it from the header they return).

#include <cstdint>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "base/error.hpp"

namespace upkie_rl {

/// Largest checkpoint file read (the largest network, kMaxParameters, with its two Adam
/// moments is 768 MB).
inline constexpr std::uintmax_t kMaxCheckpointBytes = std::uintmax_t{2} << 30;
/// Largest JSON header (normalisation statistics of the widest observation are ~2 MB).
inline constexpr std::uint64_t kMaxCheckpointHeaderBytes = std::uint64_t{16} << 20;

/// Raised for a missing, truncated, corrupted or inconsistent checkpoint.
class CheckpointError : public Error {
 public:
  using Error::Error;
};

/// A float32 tensor: its shape and its values in row-major order.
struct FloatTensor {
  std::vector<std::int64_t> shape;
  std::vector<float> values;
};

/// The contents of a checkpoint file.
struct CheckpointFile {
  nlohmann::json header = nlohmann::json::object();  ///< Free-form metadata.
  std::map<std::string, FloatTensor> tensors;        ///< By name, stored in name order.

  /// The tensor called `name`; throws CheckpointError naming it if absent or if its
  /// number of values differs from `numel` (when numel >= 0).
  const FloatTensor& tensor(const std::string& name, std::int64_t numel = -1) const;
};

/// The tensor called `name` in `tensors`, for CheckpointFile and rl's torch Checkpoint:
/// throws CheckpointError naming it if absent or if its number of values, numel_of(tensor),
/// differs from `numel` (when numel >= 0).
template <typename Tensor, typename NumelOf>
const Tensor& find_tensor(const std::map<std::string, Tensor>& tensors, const std::string& name,
                          std::int64_t numel, NumelOf numel_of) {
  const auto found = tensors.find(name);
  if (found == tensors.end()) throw CheckpointError("checkpoint has no tensor '" + name + "'");
  const std::int64_t size = numel_of(found->second);
  if (numel >= 0 && size != numel) {
    throw CheckpointError("checkpoint tensor '" + name + "' has " + std::to_string(size) +
                          " values, expected " + std::to_string(numel));
  }
  return found->second;
}

/// Writes `file` to `path` atomically (the file is either the old one or the new one, never
/// partial). Creates parent directories. Throws CheckpointError on I/O errors or a tensor
/// whose values do not match its shape.
void write_checkpoint_file(const CheckpointFile& file, const std::filesystem::path& path);

/// Reads and verifies a checkpoint file's structure: a regular file of at most
/// kMaxCheckpointBytes, magic, CRC, a JSON object header of at most
/// kMaxCheckpointHeaderBytes nested at most kMaxJsonDepth deep, tensor sizes. Throws
/// CheckpointError naming the file and the problem. The contents are checked by
/// policy/checkpoint_gate.hpp, the reader every consumer uses.
CheckpointFile read_checkpoint_file(const std::filesystem::path& path);

/// read_checkpoint_file's checks on a file's bytes (for fuzzing); `where` names it.
CheckpointFile parse_checkpoint_bytes(std::string_view bytes, const std::string& where);

}  // namespace upkie_rl
