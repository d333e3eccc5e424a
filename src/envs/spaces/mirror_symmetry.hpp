#pragma once
/// @file
/// MirrorSymmetry: how an environment's observations and actions map under its left-right
/// mirror, for training that makes a policy mirror-symmetric (ppo.mirror_augmentation).
///
/// Why: Upkie is left-right symmetric and so are its tasks' command distributions, but a
/// policy learned from scratch need not be. The from-scratch velocity policies crouched
/// with one hip ahead and one behind on two seeds of five (a "scissored" crouch, 4-7 mm
/// further from the commanded height than the symmetric ones), a choice their mirror image
/// would have made the other way. A policy trained on each sample and its mirror image
/// cannot prefer a side.

#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace upkie_rl {

/// A map of vectors that moves and negates components: out[i] = ±in[source[i]]. A mirror
/// is an involution (applied twice it is the identity), which the constructor checks.
class SignedPermutation {
 public:
  SignedPermutation() = default;
  /// Component i of the image is `in[source[i]]`, negated where `negate[i]`.
  /// @throws std::invalid_argument naming `what` when the sizes differ, a source is out of
  ///         range, or the map is not an involution.
  SignedPermutation(std::vector<std::size_t> source, std::vector<bool> negate,
                    const std::string& what);

  std::size_t size() const { return source_.size(); }
  std::span<const std::size_t> source() const { return source_; }
  bool negated(std::size_t i) const { return negate_[i]; }

  /// Writes the image of each row of `in` (rows of size()) into `out`, of the same size;
  /// allocation-free. `in` and `out` must not overlap.
  /// @throws std::invalid_argument when a size is not a multiple of size() or they differ.
  void apply(std::span<const float> in, std::span<float> out) const;

  /// This map on each of `copies` consecutive blocks of size() components (a history of
  /// observations, newest first).
  SignedPermutation repeated(std::size_t copies) const;

 private:
  std::vector<std::size_t> source_;
  std::vector<bool> negate_;
};

/// The left-right mirror of an environment's observation and action vectors.
struct MirrorSymmetry {
  SignedPermutation observation;
  SignedPermutation action;
};

}  // namespace upkie_rl
