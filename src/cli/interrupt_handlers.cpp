#include "cli/interrupt_handlers.hpp"

namespace upkie_rl::apps {

std::atomic<bool> interrupt_requested{false};

namespace {

extern "C" void request_interrupt(int) { interrupt_requested.store(true); }

}  // namespace

InterruptHandlers::InterruptHandlers() {
  interrupt_requested.store(false);
  struct sigaction action {};
  action.sa_handler = &request_interrupt;
  sigemptyset(&action.sa_mask);
  ::sigaction(SIGINT, &action, &previous_int_);
  ::sigaction(SIGTERM, &action, &previous_term_);
}

InterruptHandlers::~InterruptHandlers() {
  ::sigaction(SIGINT, &previous_int_, nullptr);
  ::sigaction(SIGTERM, &previous_term_, nullptr);
}

}  // namespace upkie_rl::apps
