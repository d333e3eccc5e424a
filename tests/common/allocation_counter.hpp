#pragma once
/// @file
/// Counts heap allocations, for the tests that check hot paths allocate nothing. It
/// replaces the global allocation functions: include it in exactly one source file of a
/// test program.

#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <new>

namespace upkie_rl::testing {

/// Allocations made by all threads since the program started.
inline std::atomic<std::size_t> all_threads_allocations{0};

/// Allocations made by the calling thread since it started.
inline thread_local std::size_t this_thread_allocations = 0;

}  // namespace upkie_rl::testing

void* operator new(std::size_t size) {
  upkie_rl::testing::all_threads_allocations.fetch_add(1, std::memory_order_relaxed);
  ++upkie_rl::testing::this_thread_allocations;
  if (void* pointer = std::malloc(size == 0 ? 1 : size)) return pointer;
  throw std::bad_alloc();
}
void operator delete(void* pointer) noexcept { std::free(pointer); }
void operator delete(void* pointer, std::size_t) noexcept { std::free(pointer); }
