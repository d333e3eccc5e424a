#include "view/client_state.hpp"

#include <stdexcept>
#include <string>

namespace upkie_rl {

namespace {

using enum ClientState;
using enum ClientEvent;

struct Transition {
  ClientState from;
  ClientEvent event;
  ClientState to;
};

// Every transition of the protocol (client_state.hpp); a pair not listed is refused.
constexpr Transition kTransitions[] = {
    {kHandshaking, kAccepted, kIdle},
    {kIdle, kTextStarted, kWritingText},
    {kIdle, kFramesStarted, kWritingFrames},
    {kIdle, kEndStarted, kWritingEnd},
    {kWritingText, kWritten, kIdle},
    {kWritingFrames, kWritten, kIdle},
    {kWritingEnd, kWritten, kClosing},
    {kIdle, kDropped, kClosed},
    {kWritingText, kDropped, kClosed},
    {kWritingFrames, kDropped, kClosed},
    {kWritingEnd, kDropped, kClosed},
    {kClosing, kDropped, kClosed},
    // A write that completed as the client was dropped changes nothing.
    {kClosed, kWritten, kClosed},
};

const char* event_name(ClientEvent event) {
  switch (event) {
    case ClientEvent::kAccepted:
      return "accepted";
    case ClientEvent::kTextStarted:
      return "text started";
    case ClientEvent::kFramesStarted:
      return "frames started";
    case ClientEvent::kEndStarted:
      return "end started";
    case ClientEvent::kWritten:
      return "written";
    case ClientEvent::kDropped:
      return "dropped";
  }
  return "unknown";
}

}  // namespace

ClientState next_client_state(ClientState state, ClientEvent event) {
  for (const Transition& transition : kTransitions) {
    if (transition.from == state && transition.event == event) return transition.to;
  }
  throw std::logic_error(std::string("viewer client: no transition from ") +
                         client_state_name(state) + " on " + event_name(event));
}

const char* client_state_name(ClientState state) {
  switch (state) {
    case ClientState::kHandshaking:
      return "handshaking";
    case ClientState::kIdle:
      return "idle";
    case ClientState::kWritingText:
      return "writing text";
    case ClientState::kWritingFrames:
      return "writing frames";
    case ClientState::kWritingEnd:
      return "writing the end";
    case ClientState::kClosing:
      return "closing";
    case ClientState::kClosed:
      return "closed";
  }
  return "unknown";
}

}  // namespace upkie_rl
