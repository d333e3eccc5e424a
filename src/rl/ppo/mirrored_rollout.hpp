#pragma once
/// @file
/// MirroredRollout: the mirror image of each sample of a rollout, and minibatches that
/// pair each sample with its image (ppo.mirror_augmentation).
///
/// Why: a left-right symmetric robot and task make the mirror image of every transition an
/// equally likely one, with the same advantage and return; training on both makes the
/// policy mirror-symmetric without a hand-written term in the loss (symmetry-based data
/// augmentation, as Mittal et al. 2024 do for legged robots in RSL-RL).
///
/// An image is a sample of the mirrored behaviour policy, whose density at the image is the
/// original's: its log π_old is the original's, and PPO's ratio π(Ma|Ms) / π_old(a|s) is the
/// importance weight of an off-policy sample. The first version evaluated π_old at the image
/// instead (π_old(Ma|Ms)), which is tiny where the policy is not yet symmetric (the action's
/// std falls to 0.06-0.09): the ratios grew without bound (approx_kl 0.8 at 1.8 M steps of
/// configs/velocity_scratch.yaml, 2.6e8 at 2.3 M, then NaN actions). V_old of an image is
/// the critic's at the image, for value clipping; its return is the original's.
///
/// Cost: each update passes over twice the samples (the same number of minibatches, each
/// twice as large), and the images' V_old is one batched pass of the critic per rollout.
/// configs/velocity_scratch.yaml (8 M steps, this 2-core machine, alone): 371 s of updates
/// in 14 min 35 s with 10 epochs of 1024 samples, against about 200 s in 9 min 52 s
/// without; the configuration's 5 epochs of 512 give 185 s in 12 min 2 s.

#include <torch/torch.h>

#include <cstdint>
#include <vector>

#include "envs/spaces/mirror_symmetry.hpp"
#include "rl/ppo/actor_critic.hpp"
#include "rl/ppo/ppo_loss.hpp"
#include "rl/ppo/rollout_buffer.hpp"

namespace upkie_rl {

class MirroredRollout {
 public:
  /// Storage for the images of a rollout of `size` samples of these spaces' mirror.
  MirroredRollout(const MirrorSymmetry& mirror, std::int64_t size);

  /// Writes the image of every sample of `buffer` (its advantages and returns computed):
  /// mirrored observations (normalised: the normaliser's statistics must be symmetric,
  /// VecNormalize::set_statistics_mirror) and actions, and their V under `policy`, which
  /// must be the one that collected the rollout.
  void fill(const RolloutBuffer& buffer, const ActorCritic& policy);

  /// The last fill()'s rollout and its images in the order of `permutation` (of the
  /// buffer's samples), by minibatches of `batch_size`: the minibatch of samples
  /// [begin, begin + n) of the permutation becomes rows [2·begin, 2·begin + 2n), those
  /// samples then their images.
  PpoMinibatch paired_shuffle(const std::vector<std::int64_t>& permutation,
                              std::int64_t batch_size);

 private:
  MirrorSymmetry mirror_;
  torch::Tensor observations_;              // size x observation_size
  torch::Tensor actions_;                   // size x action_size
  torch::Tensor values_;                    // size
  PpoMinibatch combined_;                   // [rollout; images], made once per fill()
  std::vector<std::int64_t> paired_index_;  // 2·size rows of [buffer; images]
};

}  // namespace upkie_rl
