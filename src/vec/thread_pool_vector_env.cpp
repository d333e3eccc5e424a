#include "vec/thread_pool_vector_env.hpp"

#include <stdexcept>
#include <string>

#include "base/spin_then_wait.hpp"

namespace upkie_rl {

ThreadPoolVectorEnv::ThreadPoolVectorEnv(std::vector<std::unique_ptr<Env>> envs,
                                         std::size_t threads, AutoresetMode autoreset_mode)
    : EnvBatchVectorEnv(std::move(envs), autoreset_mode), num_threads_(threads) {
  if (threads == 0 || threads > batch_.size()) {
    throw std::invalid_argument("thread pool vector env: threads must be in [1, " +
                                std::to_string(batch_.size()) + "], got " +
                                std::to_string(threads));
  }
  errors_.resize(batch_.size());
  threads_.reserve(num_threads_ - 1);
  for (std::size_t worker = 1; worker < num_threads_; ++worker) {
    threads_.emplace_back([this] { worker_loop(); });
  }
}

ThreadPoolVectorEnv::~ThreadPoolVectorEnv() {
  task_ = Task::kStop;
  generation_.fetch_add(1, std::memory_order_acq_rel);
  generation_.notify_all();
  for (std::thread& thread : threads_) thread.join();
}

void ThreadPoolVectorEnv::work() {
  // Relaxed is enough to hand out indices: the environment data each one touches is
  // published by generation_ (caller to workers) and pending_ (workers to caller).
  for (std::size_t i = next_env_.fetch_add(1, std::memory_order_relaxed); i < batch_.size();
       i = next_env_.fetch_add(1, std::memory_order_relaxed)) {
    try {
      if (task_ == Task::kReset) {
        batch_.reset(i, i + 1, seed_);
      } else {
        batch_.step(i, i + 1, actions_);
      }
    } catch (...) {
      errors_[i] = std::current_exception();
    }
  }
}

void ThreadPoolVectorEnv::worker_loop() {
  std::uint64_t seen = 0;
  while (true) {
    spin_then_wait(generation_, [seen](std::uint64_t g) { return g != seen; });
    seen = generation_.load(std::memory_order_acquire);
    if (task_ == Task::kStop) return;
    work();
    if (pending_.fetch_sub(1, std::memory_order_acq_rel) == 1) pending_.notify_one();
  }
}

void ThreadPoolVectorEnv::run(Task task) {
  task_ = task;
  for (auto& error : errors_) error = nullptr;
  next_env_.store(0, std::memory_order_relaxed);
  pending_.store(num_threads_ - 1, std::memory_order_release);
  generation_.fetch_add(1, std::memory_order_acq_rel);
  generation_.notify_all();
  work();
  spin_then_wait(pending_, [](std::size_t p) { return p == 0; });
  for (const auto& error : errors_) {
    if (error) std::rethrow_exception(error);
  }
}

std::span<const float> ThreadPoolVectorEnv::reset(std::optional<std::uint64_t> seed) {
  seed_ = seed;
  run(Task::kReset);
  batch_.mark_reset();
  return batch_.result().observations;
}

const VectorStep& ThreadPoolVectorEnv::step(std::span<const float> actions) {
  batch_.check_step(actions);
  actions_ = actions;
  run(Task::kStep);
  return batch_.result();
}

}  // namespace upkie_rl
