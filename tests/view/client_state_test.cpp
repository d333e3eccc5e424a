#include "view/client_state.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace upkie_rl {
namespace {

TEST(ClientState, AWholeLifeFromHandshakeToClose) {
  ClientState state = ClientState::kHandshaking;
  EXPECT_FALSE(is_open(state));
  state = next_client_state(state, ClientEvent::kAccepted);
  EXPECT_EQ(state, ClientState::kIdle);
  EXPECT_TRUE(is_open(state));
  EXPECT_FALSE(is_writing(state));
  state = next_client_state(state, ClientEvent::kTextStarted);
  EXPECT_EQ(state, ClientState::kWritingText);
  EXPECT_TRUE(is_writing(state));
  state = next_client_state(state, ClientEvent::kWritten);
  EXPECT_EQ(state, ClientState::kIdle);
  state = next_client_state(state, ClientEvent::kFramesStarted);
  EXPECT_EQ(state, ClientState::kWritingFrames);
  state = next_client_state(state, ClientEvent::kWritten);
  EXPECT_EQ(state, ClientState::kIdle);
  state = next_client_state(state, ClientEvent::kEndStarted);
  EXPECT_EQ(state, ClientState::kWritingEnd);
  // Nothing follows the end message but the close.
  state = next_client_state(state, ClientEvent::kWritten);
  EXPECT_EQ(state, ClientState::kClosing);
  EXPECT_TRUE(is_writing(state));  // The close exchange has the write timeout.
  EXPECT_TRUE(is_open(state));
  state = next_client_state(state, ClientEvent::kDropped);
  EXPECT_EQ(state, ClientState::kClosed);
  EXPECT_FALSE(is_open(state));
}

TEST(ClientState, EveryOpenStateCanBeDropped) {
  for (ClientState state :
       {ClientState::kIdle, ClientState::kWritingText, ClientState::kWritingFrames,
        ClientState::kWritingEnd, ClientState::kClosing}) {
    EXPECT_EQ(next_client_state(state, ClientEvent::kDropped), ClientState::kClosed)
        << client_state_name(state);
  }
}

TEST(ClientState, AWriteThatCompletesAfterTheDropChangesNothing) {
  EXPECT_EQ(next_client_state(ClientState::kClosed, ClientEvent::kWritten), ClientState::kClosed);
}

TEST(ClientState, RefusesTransitionsTheProtocolDoesNotHave) {
  // One write at a time.
  EXPECT_THROW(next_client_state(ClientState::kWritingFrames, ClientEvent::kTextStarted),
               std::logic_error);
  // Nothing is written while handshaking, closing or closed.
  EXPECT_THROW(next_client_state(ClientState::kHandshaking, ClientEvent::kFramesStarted),
               std::logic_error);
  EXPECT_THROW(next_client_state(ClientState::kClosing, ClientEvent::kTextStarted),
               std::logic_error);
  EXPECT_THROW(next_client_state(ClientState::kClosed, ClientEvent::kEndStarted), std::logic_error);
  // No write is under way to complete.
  EXPECT_THROW(next_client_state(ClientState::kIdle, ClientEvent::kWritten), std::logic_error);
  // A closed client is not dropped twice, nor accepted again.
  EXPECT_THROW(next_client_state(ClientState::kClosed, ClientEvent::kDropped), std::logic_error);
  EXPECT_THROW(next_client_state(ClientState::kIdle, ClientEvent::kAccepted), std::logic_error);
}

}  // namespace
}  // namespace upkie_rl
