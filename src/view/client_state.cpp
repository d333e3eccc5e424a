#include "view/client_state.hpp"

#include <stdexcept>
#include <string>

namespace upkie_rl {

namespace {

// The transition of a state that is not dropped, or `state` itself when `event` does not
// apply (refused by the caller).
ClientState transition(ClientState state, ClientEvent event) {
  switch (state) {
    case ClientState::kHandshaking:
      if (event == ClientEvent::kAccepted) return ClientState::kIdle;
      break;
    case ClientState::kIdle:
      if (event == ClientEvent::kTextStarted) return ClientState::kWritingText;
      if (event == ClientEvent::kFramesStarted) return ClientState::kWritingFrames;
      if (event == ClientEvent::kEndStarted) return ClientState::kWritingEnd;
      break;
    case ClientState::kWritingText:
    case ClientState::kWritingFrames:
      if (event == ClientEvent::kWritten) return ClientState::kIdle;
      break;
    case ClientState::kWritingEnd:
      if (event == ClientEvent::kWritten) return ClientState::kClosing;
      break;
    case ClientState::kClosing:
      break;
    case ClientState::kClosed:
      if (event == ClientEvent::kWritten) return ClientState::kClosed;
      break;
  }
  return state;
}

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
  if (event == ClientEvent::kDropped && is_open(state)) return ClientState::kClosed;
  const ClientState next = transition(state, event);
  const bool stays = state == ClientState::kClosed && event == ClientEvent::kWritten;
  if (next == state && !stays) {
    throw std::logic_error(std::string("viewer client: no transition from ") +
                           client_state_name(state) + " on " + event_name(event));
  }
  return next;
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
