#pragma once
/// @file
/// The spine's state machine (spine.md section 4), apart from any memory, clock or
/// simulator so that it can be tested on its own.

#include <cstdint>
#include <optional>
#include <string_view>

#include "spine/request.hpp"

namespace upkie_rl {

/// States of the spine, numbered as in the reference.
enum class SpineState : std::uint32_t {
  kSendStops = 0,  ///< Servos receive stop commands; waits for Start.
  kReset = 1,      ///< Apply a new configuration (one cycle).
  kIdle = 2,       ///< Waiting for the agent; servos keep the last action.
  kStep = 3,       ///< Apply an action (one cycle).
  kShutdown = 4,   ///< Interrupted: stop commands for a few cycles, then Over.
  kOver = 5,       ///< Done; the spine exits.
};

std::string_view spine_state_name(SpineState state);

/// Transitions of the spine. Each cycle: on_cycle_beginning(request) with the request
/// word read from memory, the spine's work for state(), then on_cycle_end(). The
/// returned values say what to write into the request word, if anything.
///
/// - Idle: None stays; Action -> Step; Start -> warn, stay, clear the request; Stop ->
///   SendStops; any other code -> request Error.
/// - SendStops: None stays; Action -> request Error; Start -> Reset once at least
///   `nb_stop_cycles` cycles were spent stopping (otherwise it stays pending); Stop ->
///   SendStops again (counter to 0); a code outside the protocol -> request Error.
/// - Reset and Step go to Idle at cycle end, which clears the request (the agent's "done").
/// - Entering SendStops clears the request, so that the agent's next wait returns.
/// - Interrupt -> Shutdown; after `nb_stop_cycles` cycles in Shutdown -> Over.
/// - A failure while in Shutdown (abort) -> Over at once.
class SpineStateMachine {
 public:
  /// Number of stop cycles required before a Start, and spent in Shutdown.
  static constexpr int kDefaultNbStopCycles = 5;

  explicit SpineStateMachine(int nb_stop_cycles = kDefaultNbStopCycles);

  SpineState state() const { return state_; }
  /// True in SendStops and Shutdown, where servos receive stop commands.
  bool is_stopped() const {
    return state_ == SpineState::kSendStops || state_ == SpineState::kShutdown;
  }
  bool is_over() const { return state_ == SpineState::kOver; }

  /// Processes the request read at the beginning of a cycle (raw: may be any value).
  /// @return The request to write, or nullopt to leave the word as it is.
  std::optional<Request> on_cycle_beginning(std::uint32_t request);

  /// Ends a cycle. @return The request to write (None when entering Idle), or nullopt.
  std::optional<Request> on_cycle_end();

  /// SIGINT, SIGTERM or an exception in a cycle: go to Shutdown (no-op once there).
  void on_interrupt();

  /// The shutdown itself failed (its stop cycles cannot run): go to Over at once, rather
  /// than retry a failing cycle forever. A no-op outside Shutdown.
  void abort();

  /// True when the last on_cycle_beginning() in Idle saw a Start (the spine warns).
  bool start_ignored() const { return start_ignored_; }

 private:
  std::optional<Request> enter(SpineState state);

  int nb_stop_cycles_;
  SpineState state_ = SpineState::kSendStops;
  int stop_cycles_ = 0;
  bool start_ignored_ = false;
};

}  // namespace upkie_rl
