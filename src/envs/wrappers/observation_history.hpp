#pragma once
/// @file
/// ObservationHistory: the last k observations side by side, newest first.
///
/// Why: a policy that sees one observation cannot tell a push from a slope or a payload
/// (each tilts the body the same way at first), nor measure how fast a lagging actuator
/// responds; with the last few observations it can (issue 33, docs/reality.md).

#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

#include "envs/wrappers/env_wrapper.hpp"

namespace upkie_rl {

/// Largest history the `observation_history` option accepts: 50 steps, a second at the
/// velocity task's 50 Hz.
inline constexpr int kMaxObservationHistory = 50;

/// Its observation is the inner environment's last `length` observations concatenated,
/// newest first: components [0, n) are the current observation (so the controllers that
/// read an observation by index, and names like "gyro.y", see it unchanged), [n, 2n) the
/// previous one ("gyro.y@t-1"), and so on. At reset every slot holds the reset observation.
/// The bounds repeat the inner space's. Steps allocate nothing.
class ObservationHistory final : public EnvWrapper {
 public:
  /// @throws std::invalid_argument on a null env or a length outside
  ///         [1, kMaxObservationHistory], naming the observation_history option.
  ObservationHistory(std::unique_ptr<Env> env, int length);

  /// Observations held (k).
  int length() const { return length_; }

  const BoxSpace& observation_space() const override { return space_; }
  /// The inner environment's mirror on each observation of the history.
  const MirrorSymmetry* mirror_symmetry() const override { return mirror_ ? &*mirror_ : nullptr; }
  void reset(std::optional<std::uint64_t> seed, std::span<float> observation) override;
  StepResult step(std::span<const float> action, std::span<float> observation) override;

 private:
  /// @throws std::invalid_argument unless `observation` has the size of space_.
  void check_size(std::span<float> observation) const;

  int length_;
  BoxSpace space_;
  std::vector<float> history_;  // length_ observations, newest first.
  std::vector<float> latest_;   // The inner environment's last observation.
  std::optional<MirrorSymmetry> mirror_;
};

}  // namespace upkie_rl
