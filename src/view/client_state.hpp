#pragma once
/// @file
/// Where one browser's WebSocket connection to the viewer server is, and the transitions
/// between those states: the whole life of a viewer client as one state machine (the
/// server's io thread drives it, view/view_client.cpp).
///
///   kHandshaking --accepted--> kIdle
///   kIdle --text/frames/end started--> kWritingText / kWritingFrames / kWritingEnd
///   kWritingText, kWritingFrames --written--> kIdle
///   kWritingEnd --written--> kClosing (close frames both ways, so that the browser reads
///                                      everything sent before)
///   any open state --dropped--> kClosed (write error or timeout, browser gone, closed)
///   kClosed --written--> kClosed (a write that completed as the client was dropped)

namespace upkie_rl {

enum class ClientState {
  kHandshaking,    ///< WebSocket handshake under way: not a client of the server yet.
  kIdle,           ///< Open, nothing being written: send() may start a write.
  kWritingText,    ///< A text message (a driving reply) being written.
  kWritingFrames,  ///< A binary message of frames being written.
  kWritingEnd,     ///< The end message being written: nothing follows it but the close.
  kClosing,        ///< Close frames being exchanged.
  kClosed,         ///< Gone: out of the server's clients.
};

enum class ClientEvent {
  kAccepted,       ///< The handshake succeeded.
  kTextStarted,    ///< A text message's write started.
  kFramesStarted,  ///< A frames message's write started.
  kEndStarted,     ///< The end message's write started.
  kWritten,        ///< The write under way completed without error.
  kDropped,        ///< The connection is dropped.
};

/// The state after `event`.
/// @throws std::logic_error for an event the state does not take (a bug of the server).
ClientState next_client_state(ClientState state, ClientEvent event);

/// Handshake done and not closed: a client of the server, which may queue messages for it.
constexpr bool is_open(ClientState state) {
  return state != ClientState::kHandshaking && state != ClientState::kClosed;
}

/// Something is being written (or the close exchanged): the write timeout applies.
constexpr bool is_writing(ClientState state) {
  return state == ClientState::kWritingText || state == ClientState::kWritingFrames ||
         state == ClientState::kWritingEnd || state == ClientState::kClosing;
}

/// Name of the state, for messages.
const char* client_state_name(ClientState state);

}  // namespace upkie_rl
