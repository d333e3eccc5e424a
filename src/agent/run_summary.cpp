#include "agent/run_summary.hpp"

#include <cstdio>

namespace upkie_rl {

std::string RunSummary::to_string() const {
  char text[256];
  std::snprintf(text, sizeof(text),
                "summary: %lld cycles, loop period mean %.3f ms, p99 %.3f ms, max %.3f ms, "
                "%lld deadline misses, %d stop cycles sent; stopped: ",
                static_cast<long long>(loop.cycles), loop.mean_period * 1e3, loop.p99_period * 1e3,
                loop.max_period * 1e3, static_cast<long long>(loop.deadline_misses),
                stop_cycles_sent);
  return text + stop_reason;
}

}  // namespace upkie_rl
