#pragma once
/// @file
/// The one gate every checkpoint passes before anything uses it: `train --resume`
/// (rl/runs/checkpoint.hpp's load_checkpoint), and `rollout`, `evaluate`, `sweep` and the
/// Python `load_policy` through DeployedPolicy, so a checkpoint either loads everywhere or
/// is refused everywhere with the same message. A robot runner should load policies
/// with DeployedPolicy::load (or read_checked_checkpoint) too.
///
/// Beyond the file's structure (read_checkpoint_file: size, magic, CRC, header size and
/// nesting depth) it checks the contents: the known format and version, a readable
/// configuration, a network within policy/network_limits.hpp whose sizes match the stored
/// spaces, spaces with ordered bounds (finite for actions), tensors of the network's size,
/// every weight, moment and statistic finite, Adam's moments consistent
/// (kMaxAdamMomentRatio), normalisation settings in range, actor and
/// critic outputs proven finite for every input in range and log σ in [-20, 20]
/// (policy/network_output_bound.hpp), and counters in [0, kMaxCheckpointCounter]. Header keys it
/// does not know are left alone (later versions of the writer may add optional ones, such as
/// provenance).

#include <cstdint>
#include <filesystem>
#include <string>

#include "policy/checkpoint_file.hpp"

namespace upkie_rl {

/// The header's "version" of the checkpoints this build reads and writes.
inline constexpr std::int64_t kCheckpointVersion = 1;
/// Largest counter (timesteps, iterations, updates, checkpoints, optimiser steps) accepted:
/// far beyond any run, far from int64 overflow.
inline constexpr std::int64_t kMaxCheckpointCounter = 1'000'000'000'000'000;
/// Largest m² / v accepted for the optimiser's moments m (optimizer.exp_avg) and v
/// (optimizer.exp_avg_sq ≥ 0), beyond an absolute slack of kAdamMomentSlack on |m|. Adam's
/// recurrences from zero bound m² by (1 − β1)² / ((1 − β2)(1 − β1² / β2)) · v for any
/// gradients: 52.9 for PPO's β = (0.9, 0.999) (rl/ppo/flat_adam.hpp checks its own betas against
/// this limit). A crafted checkpoint outside it (a negative v, or a large m over a tiny v)
/// would make the first update after resume NaN or arbitrarily large.
inline constexpr double kMaxAdamMomentRatio = 64.0;
/// Absolute slack on |m|: float32 moments of gradients below about 1e-19 underflow v to 0
/// first. With PPO's eps = 1e-5 it still bounds the first update's step to lr · 0.1.
inline constexpr double kAdamMomentSlack = 1e-6;

/// Checks a checkpoint's contents (see the file comment). Throws CheckpointError whose
/// message starts with `where` and names the first problem.
void check_checkpoint(const CheckpointFile& file, const std::string& where);

/// Rethrows the exception being handled as a CheckpointError whose message starts with
/// "<where>: ": a CheckpointError's or std::invalid_argument's message as it is, a JSON
/// error's after "malformed header: "; any other exception unchanged. For the catch (...)
/// of the readers of a checkpoint's contents (the gate, DeployedPolicy), so that they word
/// a problem alike.
[[noreturn]] void rethrow_as_checkpoint_error(const std::string& where);

/// read_checkpoint_file, then check_checkpoint with `where` = "checkpoint <path>".
CheckpointFile read_checked_checkpoint(const std::filesystem::path& path);

}  // namespace upkie_rl
