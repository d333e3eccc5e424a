#pragma once
/// @file
/// EndNotice: the end of a run as the viewer server tells it (a text message
/// {"type": "end", "reason": ...} after each browser's remaining frames), and which of the
/// browsers connected then have not had it yet. Lives on the server's io thread.

#include <string>
#include <unordered_set>

namespace upkie_rl {

class ViewClient;

class EndNotice {
 public:
  using Audience = std::unordered_set<const ViewClient*>;

  /// Posts the end with `reason` to `audience`, the browsers connected now (later ones get
  /// it too, but nobody waits for them).
  void post(const std::string& reason, Audience audience);
  /// The end message, or null before post().
  const std::string* message() const { return posted_ ? &message_ : nullptr; }
  /// Takes `client` out of the audience; returns whether it was in it.
  bool delivered(const ViewClient* client) { return audience_.erase(client) > 0; }

 private:
  bool posted_ = false;
  std::string message_;
  Audience audience_;
};

}  // namespace upkie_rl
