// PpoGradient::compute on one and on two update threads (ppo.update_threads), side by side
// in one run: each iteration times a few minibatches on one thread, then the same on two,
// so that the machine's load falls on both alike. Wall time, not CPU time: the second
// thread's work is the point, and it is not on the caller's CPU clock. The counters give
// each one's milliseconds per minibatch and their ratio (one / two: above 1, two threads
// are faster). It needs a free core to show anything: on a machine whose cores are all busy
// the two threads share one. docs/training.md quotes the figures.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdint>

#include "rl/ppo/actor_critic.hpp"
#include "rl/ppo/ppo_gradient.hpp"
#include "rl/ppo/ppo_loss.hpp"

namespace {

using namespace upkie_rl;

constexpr int kMinibatchesPerTiming = 8;

// Random observations, actions near the policy's means, advantages of either sign.
PpoMinibatch random_minibatch(const ActorCritic& policy, std::int64_t rows) {
  torch::NoGradGuard no_grad;
  torch::manual_seed(5);
  PpoMinibatch batch;
  batch.observations = torch::randn({rows, policy.observation_size()});
  const torch::Tensor mean = policy.action_mean(batch.observations);
  batch.actions = mean + 0.3 * torch::randn(mean.sizes());
  const ActionEvaluation evaluation = policy.evaluate_actions(batch.observations, batch.actions);
  batch.old_log_prob = evaluation.log_prob + 0.05 * torch::randn({rows});
  batch.old_values = evaluation.values + 0.1 * torch::randn({rows});
  batch.advantages = torch::randn({rows});
  batch.returns = batch.old_values + torch::randn({rows});
  return batch;
}

// Wall seconds of kMinibatchesPerTiming computes by `gradient`.
double time_minibatches(PpoGradient& gradient, const PpoMinibatchView& minibatch,
                        ActorCritic& policy, const PpoConfig& ppo) {
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < kMinibatchesPerTiming; ++i) {
    benchmark::DoNotOptimize(gradient.compute(minibatch, policy, ppo).total);
  }
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Arguments: observation size, action size, hidden width (two hidden layers, actor and
// critic), minibatch rows: the velocity task's tanh networks (21, 6, 128) on its minibatches
// of 1024, and the pendulum's (4, 1, 64) on its minibatches of 128.
void BM_PpoGradientUpdateThreads(benchmark::State& state) {
  torch::set_num_threads(1);
  PolicyConfig config;
  config.actor_hidden_sizes = {state.range(2), state.range(2)};
  config.critic_hidden_sizes = config.actor_hidden_sizes;
  config.activation = Activation::kTanh;
  ActorCritic policy(state.range(0), state.range(1), config, 0);
  const std::int64_t rows = state.range(3);
  const PpoMinibatch batch = random_minibatch(policy, rows);
  const PpoMinibatchView minibatch = view_minibatch(batch);
  const PpoConfig ppo;
  PpoGradient one(policy, rows, PpoGradientKernel::kFastest, 1);
  PpoGradient two(policy, rows, PpoGradientKernel::kFastest, 2);
  one.compute(minibatch, policy, ppo);  // Warms the caches and wakes the companion once.
  two.compute(minibatch, policy, ppo);
  double one_seconds = 0.0, two_seconds = 0.0;
  for (auto _ : state) {
    one_seconds += time_minibatches(one, minibatch, policy, ppo);
    two_seconds += time_minibatches(two, minibatch, policy, ppo);
  }
  const double minibatches = static_cast<double>(state.iterations() * kMinibatchesPerTiming);
  state.counters["one_thread_ms"] = 1e3 * one_seconds / minibatches;
  state.counters["two_threads_ms"] = 1e3 * two_seconds / minibatches;
  state.counters["one/two"] = one_seconds / two_seconds;
  state.counters["avx2"] = one.uses_avx2() ? 1 : 0;
}
BENCHMARK(BM_PpoGradientUpdateThreads)
    ->ArgNames({"obs", "act", "hidden", "rows"})
    ->Args({21, 6, 128, 1024})
    ->Args({4, 1, 64, 128})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
