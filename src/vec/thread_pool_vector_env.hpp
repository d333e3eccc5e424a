#pragma once
/// @file
/// ThreadPoolVectorEnv: n environments stepped by a fixed pool of threads (EnvPool style).

#include <atomic>
#include <exception>
#include <thread>
#include <vector>

#include "vec/env_batch.hpp"
#include "vec/vector_env.hpp"

namespace upkie_rl {

/// Worker w always steps the same contiguous block of environments, [w·n/T, (w+1)·n/T);
/// the calling thread is worker 0. Environments know nothing of threads, and each one is
/// stepped exactly as SyncVectorEnv steps it, so results are bit-identical to it for the
/// same seeds. An exception thrown by an environment is re-thrown by step()/reset() (the
/// one of the lowest environment index), after every worker has finished.
class ThreadPoolVectorEnv final : public VectorEnv {
 public:
  /// @param threads Number of workers including the caller, in [1, envs.size()].
  /// @throws std::invalid_argument on a bad thread count.
  ThreadPoolVectorEnv(std::vector<std::unique_ptr<Env>> envs, std::size_t threads);
  ~ThreadPoolVectorEnv() override;
  ThreadPoolVectorEnv(const ThreadPoolVectorEnv&) = delete;
  ThreadPoolVectorEnv& operator=(const ThreadPoolVectorEnv&) = delete;

  std::size_t num_envs() const override { return batch_.size(); }
  const BoxSpace& observation_space() const override { return batch_.observation_space(); }
  const BoxSpace& action_space() const override { return batch_.action_space(); }
  std::span<const float> reset(std::uint64_t seed) override;
  const VectorStep& step(std::span<const float> actions) override;

  std::size_t num_threads() const { return num_threads_; }
  const Env& env(std::size_t i) const { return batch_.env(i); }

 private:
  enum class Task { kReset, kStep, kStop };

  void run(Task task);            // Runs `task` on every worker and waits.
  void work(std::size_t worker);  // Does the current task for one worker's block.
  void worker_loop(std::size_t worker);
  std::size_t block_begin(std::size_t worker) const {
    return worker * batch_.size() / num_threads_;
  }

  EnvBatch batch_;
  std::size_t num_threads_;
  std::vector<std::thread> threads_;
  // Current task, written by the caller before bumping generation_.
  Task task_ = Task::kStep;
  std::uint64_t seed_ = 0;
  std::span<const float> actions_;
  std::vector<std::exception_ptr> errors_;  // One per worker.
  std::atomic<std::uint64_t> generation_{0};
  std::atomic<std::size_t> pending_{0};
};

}  // namespace upkie_rl
