#pragma once
/// @file
/// The gradient of the PPO loss (rl/ppo/ppo_loss.hpp) with respect to every parameter of an
/// ActorCritic, by a hand-written forward and backward pass in float32.
///
/// Why: with 64x64 MLPs and minibatches of 128 rows, libtorch's autograd engine and
/// dispatcher cost more than the arithmetic itself (about 60% of an update's instructions,
/// the rest being sgemm on tiny matrices). This computes the same loss and gradients with
/// no graph, no dispatch and no allocation, following torch's conventions at ties and
/// bounds (torch.min of equal values splits the gradient in halves, clamp passes the
/// gradient at its bounds, relu passes none at zero), so that it can replace
/// `compute_ppo_loss(...).total.backward()` in the training loop. compute_ppo_loss stays
/// the reference; tests/rl/ppo_gradient_test.cpp compares the two.
///
/// The matrix products use Eigen, or, on CPUs with AVX2 and FMA, the register-blocked
/// kernels of rl/ppo/matrix_kernels_avx2.hpp, chosen at run time: the project is built for
/// baseline x86-64, where Eigen only has SSE2 and spends more instructions on these products
/// than libtorch's AVX2 sgemm did (about 1.4 per multiply-add against 0.25 for the kernel).
///
/// It covers the relu and tanh activations only and refuses the others, which train through
/// rl/ppo/autograd_ppo_gradient.hpp (`ppo.gradient` in docs/training.md).
///
/// The actor's part (its forward pass, the policy and entropy terms, its backward pass) and
/// the critic's (forward pass, value term, backward pass) read the same minibatch and
/// parameters and write disjoint ranges of the flat gradient, each with buffers of its own:
/// with 2 update threads (`ppo.update_threads`) the critic's runs on a companion thread
/// (base/companion_thread.hpp) beside the actor's. Each part does the same arithmetic in the
/// same order on either thread, so the gradient and the loss terms are bit for bit those of
/// one thread.

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "base/companion_thread.hpp"
#include "policy/mlp.hpp"
#include "policy/parameter_layout.hpp"
#include "rl/ppo/actor_critic.hpp"
#include "rl/ppo/ppo_loss.hpp"
#include "rl/runs/training_config.hpp"

namespace upkie_rl {

/// One minibatch as raw float32 rows (no tensors), in the layout of PpoMinibatch:
/// row-major observations and actions, one value per sample for the rest.
struct PpoMinibatchView {
  std::int64_t size = 0;                ///< Number of samples.
  std::span<const float> observations;  ///< size x observation_size (normalised).
  std::span<const float> actions;       ///< size x action_size (unclipped samples).
  std::span<const float> old_log_prob;  ///< size: log π_old(a|s).
  std::span<const float> old_values;    ///< size: V at collection time.
  std::span<const float> advantages;    ///< size: GAE advantages (not normalised).
  std::span<const float> returns;       ///< size: value targets A + V.

  /// Samples [begin, begin + length): a minibatch of a shuffled rollout, without copying.
  PpoMinibatchView rows(std::int64_t begin, std::int64_t length) const;
};

/// Views the tensors of `batch`, which must be contiguous float32 on the CPU (throws
/// std::invalid_argument otherwise). The tensors must outlive the view.
PpoMinibatchView view_minibatch(const PpoMinibatch& batch);

/// The terms of the loss on one minibatch, the same as PpoLoss's but as plain numbers.
struct PpoLossStatistics {
  double total = 0.0;                 ///< L_pg + c_ent·L_ent + c_v·L_v.
  double policy_gradient_loss = 0.0;  ///< −mean(min(A·ρ, A·clamp(ρ, 1 ± ε))).
  double value_loss = 0.0;            ///< mean((R − V_pred)²), V_pred clipped around V_old.
  double entropy_loss = 0.0;          ///< −entropy.
  double approx_kl = 0.0;             ///< mean((ρ − 1) − log ρ).
  double clip_fraction = 0.0;         ///< mean(|ρ − 1| > ε).
};

/// How PpoGradient multiplies matrices.
enum class PpoGradientKernel {
  /// The AVX2/FMA kernel when the CPU has both, else Eigen.
  kFastest,
  /// Eigen whatever the CPU: the fallback, selectable so that tests cover it everywhere.
  kPortable,
};

/// Computes the PPO loss and writes its gradient into ActorCritic::flat_gradients().
/// Made once and reused for every minibatch: every intermediate buffer is sized for
/// `max_batch_size` rows in the constructor, so a call allocates nothing; with 2 update
/// threads the constructor also starts the companion thread (the destructor joins it), so a
/// call creates no thread either.
class PpoGradient {
 public:
  /// Buffers for minibatches of up to `max_batch_size` samples of policies shaped like
  /// `policy` (its sizes and hidden layers; the weights are read at each call), computed on
  /// `update_threads` threads: 1 (the caller's) or 2 (the caller's and a companion thread
  /// started here, that runs the critic's part; same results bit for bit).
  /// Throws std::invalid_argument when covers(policy's activation) is false or
  /// update_threads is neither 1 nor 2.
  PpoGradient(const ActorCritic& policy, std::int64_t max_batch_size,
              PpoGradientKernel kernel = PpoGradientKernel::kFastest,
              std::int64_t update_threads = 1);

  /// Whether the hand-written backward pass knows this activation's derivative.
  static bool covers(Activation activation);

  /// Evaluates `policy` on `batch`, then overwrites policy.flat_gradients() with the
  /// gradient of compute_ppo_loss(policy.evaluate_actions(...), batch, config).total
  /// (no need to zero it first) and returns the loss terms. Throws std::invalid_argument
  /// when the batch is empty, larger than max_batch_size(), has spans of the wrong sizes,
  /// or the policy is not shaped like the constructor's (sizes and activation).
  PpoLossStatistics compute(const PpoMinibatchView& batch, ActorCritic& policy,
                            const PpoConfig& config);

  std::int64_t max_batch_size() const { return max_batch_size_; }
  /// Whether the matrix products run on the AVX2/FMA kernel rather than on Eigen.
  bool uses_avx2() const { return avx2_; }
  /// Threads compute() runs on: 1, or 2 with the critic's part on the companion thread.
  std::int64_t update_threads() const { return companion_ ? 2 : 1; }

 private:
  /// One network's buffers, sized once for max_batch_size rows. The actor and the critic
  /// each have their own, so that their passes can run at the same time.
  struct NetworkScratch {
    NetworkScratch(const Mlp& mlp, std::int64_t max_batch_size);
    /// [i]: layer i's output (after the activation for hidden layers), max_batch_size x
    /// layer i's width, row-major.
    std::vector<std::vector<float>> outputs;
    /// ∂L/∂z (z: pre-activation output) of the layer being back-propagated and of the one
    /// below it, each max_batch_size x (the network's widest layer), row-major, swapped
    /// after each layer. The output layer's is ∂L/∂μ or ∂L/∂V.
    std::vector<float> output_gradient;
    std::vector<float> input_gradient;
    /// One layer's weights transposed (in x out, row-major) for the AVX2 forward pass, or
    /// ∂Wᵀ of a layer with few inputs in the backward pass: the network's largest layer.
    std::vector<float> transposed_weight;
  };
  bool same_shape(const ActorCritic& policy) const;
  void check_batch(const PpoMinibatchView& batch, const ActorCritic& policy) const;
  void forward(const Mlp& mlp, NetworkScratch& scratch, const float* parameters, const float* input,
               std::int64_t rows) const;
  void backward(const Mlp& mlp, NetworkScratch& scratch, const float* parameters,
                const float* input, std::int64_t rows, float* gradients) const;
  /// The actor's forward pass, the policy and entropy terms (∂L/∂log σ straight into
  /// `gradients`) and the actor's backward pass; returns the statistics of the policy's
  /// terms (all but value_loss and total). Writes actor_, log_prob_gradient_, advantages_
  /// and the actor's and log σ's ranges of `gradients` only.
  PpoLossStatistics actor_part(const PpoMinibatchView& batch, const float* parameters,
                               const PpoConfig& config, float* gradients);
  /// The critic's forward pass, the value term and its backward pass; returns value_loss.
  /// Writes critic_ and the critic's range of `gradients` only.
  double critic_part(const PpoMinibatchView& batch, const float* parameters,
                     const PpoConfig& config, float* gradients);

  bool avx2_;
  std::int64_t max_batch_size_;
  /// The policy's shape, held once: its layers, activation, sizes and flat layout.
  ActorCriticNetworks networks_;
  NetworkScratch actor_;
  NetworkScratch critic_;
  // The actor's per-sample scratch: ∂L/∂log π(a|s) and normalised advantages.
  std::vector<double> log_prob_gradient_;
  std::vector<float> advantages_;
  /// Runs critic_part beside actor_part with 2 update threads; null with 1.
  std::unique_ptr<CompanionThread> companion_;
};

}  // namespace upkie_rl
