#pragma once
/// @file
/// spin_then_wait: how a thread waits for another's short piece of work (an environment
/// step, half of a PPO gradient), shared by vec/thread_pool_vector_env and
/// base/companion_thread.

#include <atomic>

namespace upkie_rl {

/// Spins this many times before sleeping on a futex: the work waited for takes tens of
/// microseconds to milliseconds, so a short spin (a few microseconds) saves the wake-up
/// latency without burning a shared core for long.
inline constexpr int kSpinCount = 4000;

/// Returns once `done(value)` holds, reading `value` with acquire ordering: polls it
/// kSpinCount times, then sleeps in std::atomic::wait until a notify changes it.
template <typename T, typename Predicate>
void spin_then_wait(const std::atomic<T>& value, Predicate done) {
  for (int i = 0; i < kSpinCount; ++i) {
    if (done(value.load(std::memory_order_acquire))) return;
  }
  for (T seen = value.load(std::memory_order_acquire); !done(seen);
       seen = value.load(std::memory_order_acquire)) {
    value.wait(seen, std::memory_order_acquire);
  }
}

}  // namespace upkie_rl
