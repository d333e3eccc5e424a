#include "cli/stuck_process_exit.hpp"

#include <cstdio>
#include <cstdlib>

namespace upkie_rl::apps {

void exit_stuck_process(const std::string& message) {
  std::fprintf(stderr, "upkie-rl: error: %s\n", message.c_str());
  std::fflush(stderr);
  std::_Exit(1);
}

}  // namespace upkie_rl::apps
