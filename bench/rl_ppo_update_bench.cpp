// The gradient work of one PPO update (5 epochs over a 2048-sample rollout in minibatches
// of 128) by the three ways the trainer can compute it, measured side by side in one run:
// the hand-written gradient on its AVX2/FMA kernel, the same on Eigen alone (the build's
// baseline x86-64, SSE2), and libtorch's autograd (ppo.gradient: autograd). Each iteration
// runs the three in turn on the same rollout, so that the machine's load falls on all of
// them alike; the counters give each one's CPU time per update (milliseconds) and the
// ratios between them. The Adam step and the clipping, the same for all three, are left out.
// docs/training.md quotes the figures.
#include <benchmark/benchmark.h>

#include <array>
#include <ctime>
#include <memory>

#include "rl/ppo/actor_critic.hpp"
#include "rl/ppo/autograd_ppo_gradient.hpp"
#include "rl/ppo/ppo_gradient.hpp"
#include "rl/ppo/ppo_loss.hpp"

namespace {

using namespace upkie_rl;

constexpr std::int64_t kRolloutSize = 2048;
constexpr std::int64_t kBatchSize = 128;
constexpr std::int64_t kEpochs = 5;

// A rollout of random data shaped like the policy's (observations normalised, actions near
// the policy's means, advantages of either sign).
struct Rollout {
  PpoMinibatch tensors;
  PpoMinibatchView view;
};

Rollout random_rollout(const ActorCritic& policy) {
  torch::NoGradGuard no_grad;
  torch::manual_seed(5);
  Rollout rollout;
  PpoMinibatch& batch = rollout.tensors;
  batch.observations = torch::randn({kRolloutSize, policy.observation_size()});
  const torch::Tensor mean = policy.action_mean(batch.observations);
  batch.actions = mean + torch::randn(mean.sizes());
  const ActionEvaluation evaluation = policy.evaluate_actions(batch.observations, batch.actions);
  batch.old_log_prob = evaluation.log_prob + 0.05 * torch::randn({kRolloutSize});
  batch.old_values = evaluation.values + 0.1 * torch::randn({kRolloutSize});
  batch.advantages = torch::randn({kRolloutSize});
  batch.returns = batch.old_values + torch::randn({kRolloutSize});
  rollout.view = view_minibatch(batch);
  return rollout;
}

// CPU seconds of this thread: other processes on a loaded machine do not count, which wall
// time would (the trainer runs libtorch on this one thread too: torch_threads 1).
double thread_seconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

// CPU seconds of one update's gradients by `hand`, or by autograd when it is null.
double time_update(PpoGradient* hand, const Rollout& rollout, ActorCritic& policy,
                   const PpoConfig& ppo) {
  const double start = thread_seconds();
  for (std::int64_t epoch = 0; epoch < kEpochs; ++epoch) {
    for (std::int64_t begin = 0; begin < kRolloutSize; begin += kBatchSize) {
      const PpoMinibatchView minibatch = rollout.view.rows(begin, kBatchSize);
      const PpoLossStatistics loss = hand != nullptr
                                         ? hand->compute(minibatch, policy, ppo)
                                         : autograd_ppo_gradient(minibatch, policy, ppo);
      benchmark::DoNotOptimize(loss.total);
    }
  }
  return thread_seconds() - start;
}

// Arguments: observation size, action size, hidden width (two hidden layers, actor and
// critic), as the pendulum (4, 1, 64) and servos (larger) configurations.
void BM_PpoUpdateGradients(benchmark::State& state) {
  torch::set_num_threads(1);
  PolicyConfig config;
  config.actor_hidden_sizes = {state.range(2), state.range(2)};
  config.critic_hidden_sizes = config.actor_hidden_sizes;
  ActorCritic policy(state.range(0), state.range(1), config, 0);
  const Rollout rollout = random_rollout(policy);
  const PpoConfig ppo;
  PpoGradient avx2(policy, kBatchSize, PpoGradientKernel::kFastest);
  PpoGradient eigen(policy, kBatchSize, PpoGradientKernel::kPortable);
  if (!avx2.uses_avx2()) {
    state.SkipWithError("this CPU has no AVX2 and FMA");
    return;
  }
  std::array<double, 3> seconds{};  // AVX2, Eigen, autograd.
  for (auto _ : state) {
    seconds[0] += time_update(&avx2, rollout, policy, ppo);
    seconds[1] += time_update(&eigen, rollout, policy, ppo);
    seconds[2] += time_update(nullptr, rollout, policy, ppo);
  }
  const auto updates = static_cast<double>(state.iterations());
  state.counters["avx2_ms"] = 1e3 * seconds[0] / updates;
  state.counters["eigen_ms"] = 1e3 * seconds[1] / updates;
  state.counters["autograd_ms"] = 1e3 * seconds[2] / updates;
  state.counters["eigen/avx2"] = seconds[1] / seconds[0];
  state.counters["autograd/avx2"] = seconds[2] / seconds[0];
  state.counters["autograd/eigen"] = seconds[2] / seconds[1];
}
BENCHMARK(BM_PpoUpdateGradients)
    ->ArgNames({"obs", "act", "hidden"})
    ->Args({4, 1, 64})
    ->Args({12, 6, 128})
    ->Unit(benchmark::kMillisecond);

}  // namespace
