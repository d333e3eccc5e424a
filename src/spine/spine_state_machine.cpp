#include "spine/spine_state_machine.hpp"

namespace upkie_rl {

std::string_view spine_state_name(SpineState state) {
  switch (state) {
    case SpineState::kSendStops:
      return "SendStops";
    case SpineState::kReset:
      return "Reset";
    case SpineState::kIdle:
      return "Idle";
    case SpineState::kStep:
      return "Step";
    case SpineState::kShutdown:
      return "Shutdown";
    case SpineState::kOver:
      return "Over";
  }
  return "unknown";
}

SpineStateMachine::SpineStateMachine(int nb_stop_cycles) : nb_stop_cycles_(nb_stop_cycles) {}

std::optional<Request> SpineStateMachine::enter(SpineState state) {
  state_ = state;
  switch (state) {
    case SpineState::kSendStops:
      stop_cycles_ = 0;
      return Request::kNone;
    case SpineState::kShutdown:
      stop_cycles_ = 0;
      return std::nullopt;
    case SpineState::kIdle:
      return Request::kNone;
    default:
      return std::nullopt;
  }
}

std::optional<Request> SpineStateMachine::on_cycle_beginning(std::uint32_t request) {
  start_ignored_ = false;
  const auto code = static_cast<Request>(request);
  switch (state_) {
    case SpineState::kIdle:
      switch (code) {
        case Request::kNone:
          return std::nullopt;
        case Request::kAction:
          return enter(SpineState::kStep);
        case Request::kStart:
          start_ignored_ = true;
          return Request::kNone;
        case Request::kStop:
          return enter(SpineState::kSendStops);
        default:
          return Request::kError;
      }
    case SpineState::kSendStops:
      switch (code) {
        case Request::kNone:
        case Request::kError:
          return std::nullopt;
        case Request::kAction:
          return Request::kError;
        case Request::kStart:
          if (stop_cycles_ >= nb_stop_cycles_) return enter(SpineState::kReset);
          return std::nullopt;  // pending until enough stop cycles
        case Request::kStop:
          return enter(SpineState::kSendStops);
        default:
          return Request::kError;
      }
    default:  // Reset and Step last one cycle; Shutdown and Over ignore requests
      return std::nullopt;
  }
}

std::optional<Request> SpineStateMachine::on_cycle_end() {
  switch (state_) {
    case SpineState::kSendStops:
      ++stop_cycles_;
      return std::nullopt;
    case SpineState::kReset:
    case SpineState::kStep:
      return enter(SpineState::kIdle);
    case SpineState::kShutdown:
      if (++stop_cycles_ >= nb_stop_cycles_) state_ = SpineState::kOver;
      return std::nullopt;
    default:
      return std::nullopt;
  }
}

void SpineStateMachine::on_interrupt() {
  if (state_ != SpineState::kShutdown && state_ != SpineState::kOver) {
    enter(SpineState::kShutdown);
  }
}

void SpineStateMachine::abort() {
  if (state_ == SpineState::kShutdown) state_ = SpineState::kOver;
}

}  // namespace upkie_rl
