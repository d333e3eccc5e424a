#pragma once
/// @file
/// ThreadPoolVectorEnv: n environments stepped by a fixed pool of threads (EnvPool style).

#include <atomic>
#include <exception>
#include <thread>
#include <vector>

#include "vec/env_batch_vector_env.hpp"

namespace upkie_rl {

/// Workers (the calling thread is one of them) claim environments one at a time from a
/// shared counter until all are stepped, so a slow environment (an auto-reset rebuilding
/// its world, more contacts) or a busy core does not hold the others back. Environments
/// know nothing of threads, and each one is stepped exactly as SyncVectorEnv steps it, so
/// results are bit-identical to it for the same seeds whichever thread steps it. Every
/// environment is stepped even when another throws; the exception of the lowest
/// environment index is then re-thrown by step()/reset().
class ThreadPoolVectorEnv final : public EnvBatchVectorEnv {
 public:
  /// @param threads Number of workers including the caller, in [1, envs.size()].
  /// @throws std::invalid_argument on a bad thread count.
  ThreadPoolVectorEnv(std::vector<std::unique_ptr<Env>> envs, std::size_t threads,
                      AutoresetMode autoreset_mode = AutoresetMode::kSameStep);
  ~ThreadPoolVectorEnv() override;
  ThreadPoolVectorEnv(const ThreadPoolVectorEnv&) = delete;
  ThreadPoolVectorEnv& operator=(const ThreadPoolVectorEnv&) = delete;

  std::span<const float> reset(std::optional<std::uint64_t> seed) override;
  const VectorStep& step(std::span<const float> actions) override;

  std::size_t num_threads() const { return num_threads_; }

 private:
  enum class Task { kReset, kStep, kStop };

  void run(Task task);  // Runs `task` on every worker and waits.
  void work();          // Claims and processes environments until none is left.
  void worker_loop();

  std::size_t num_threads_;
  std::vector<std::thread> threads_;
  // Current task, written by the caller before bumping generation_.
  Task task_ = Task::kStep;
  std::optional<std::uint64_t> seed_;
  std::span<const float> actions_;
  std::vector<std::exception_ptr> errors_;  // One per environment.
  std::atomic<std::size_t> next_env_{0};    // Next environment to claim.
  std::atomic<std::uint64_t> generation_{0};
  std::atomic<std::size_t> pending_{0};
};

}  // namespace upkie_rl
