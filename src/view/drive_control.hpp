#pragma once
/// @file
/// DriveControl: the hand-over of a page's driving commands from the viewer's server thread
/// to the simulation loop of `upkie-rl drive`. The server passes it each text message of a
/// page; it checks the message (drive_message.hpp), the page's rate (RateLimiter) and its
/// right to drive (DriverArbiter), and keeps the latest command for the loop to take.

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>

#include "view/drive_protocol.hpp"
#include "view/driver_arbiter.hpp"
#include "view/rate_limiter.hpp"

namespace upkie_rl {

/// How many messages a page may send (RateLimiter per page).
struct DriveRateSettings {
  double messages_per_second = 60.0;  ///< Sustained: above the page's 50 Hz sending.
  double burst = 30.0;                ///< Messages at once (key presses in a row).
};

/// What the simulation loop takes at a step.
struct DriveInputs {
  double forward_velocity = 0.0;  ///< The command to follow [m/s].
  double yaw_rate = 0.0;          ///< [rad/s]
  double height = 0.557;          ///< Base height [m] (the limits' top until a page sets one).
  std::uint64_t sequence = 0;     ///< The page's number of that command (0: none yet).
  bool new_command = false;  ///< A command (or the zero of a release) came since the last take.
  bool reset = false;        ///< The driver asked for a new episode.
  bool paused = false;       ///< The driver paused the run.
  std::optional<double> push_heading;  ///< The driver pushed: direction in the robot's frame [rad].
};

/// Pushes a page may have waiting for the loop: each push sent is applied, one per step, so
/// two quick ones (B, then a click) both happen; more than this is a flood and is refused.
inline constexpr std::size_t kMaxWaitingPushes = 4;

/// Counters of a DriveControl.
struct DriveStatistics {
  std::uint64_t commands = 0;      ///< Accepted commands.
  std::uint64_t refused = 0;       ///< Malformed, out of range, or from a page that watches.
  std::uint64_t rate_limited = 0;  ///< Over the page's rate.
  std::uint64_t applied = 0;       ///< Commands taken by the loop (latency samples).
  double latency_sum = 0.0;        ///< Message received to command applied, summed [s].
  double latency_max = 0.0;        ///< [s]
};

class DriveControl {
 public:
  using Clock = std::chrono::steady_clock;
  using ClientId = DriverArbiter::ClientId;

  /// @throws ViewError on limits that are not finite and positive, or a bad rate.
  explicit DriveControl(const DriveLimits& limits, const DriveRateSettings& rate = {});

  const DriveLimits& limits() const { return limits_; }

  /// What receive() asks the server to send.
  struct Reply {
    std::string to_sender;        ///< A refusal, or empty.
    bool status_changed = false;  ///< Every page should get its status_message() again.
  };

  /// Server thread: a text message of page `client`.
  Reply receive(ClientId client, std::string_view text, Clock::time_point now);

  /// Server thread: page `client` went away. When it drove, control is free and the command
  /// goes to zero (and the run resumes if paused); returns whether statuses changed.
  bool disconnect(ClientId client);

  /// The drive_status message for page `client` (its role, whether paused).
  std::string status_message(ClientId client) const;

  /// Simulation loop: the latest command and the requests since the last take (a reset is
  /// taken once; pushes one per take, oldest first, none while paused).
  DriveInputs take();

  /// Simulation loop: the command of `inputs` is in the simulation now. Counts its latency
  /// and, for a page's new command, queues its acknowledgement and calls the listener.
  void applied(const DriveInputs& inputs, Clock::time_point now);

  /// Called (on the simulation loop's thread) when an acknowledgement is queued.
  void set_applied_listener(std::function<void()> listener);

  /// Server thread: the queued acknowledgement, {page, message}, if any.
  std::optional<std::pair<ClientId, std::string>> take_acknowledgement();

  DriveStatistics statistics() const;

 private:
  Reply handle(ClientId client, std::string_view text, Clock::time_point now);

  DriveLimits limits_;
  DriveRateSettings rate_;
  mutable std::mutex mutex_;
  DriverArbiter arbiter_;
  /// A page's rate: its bucket, and whether it was told it is over it (until it is not).
  struct PageRate {
    RateLimiter limiter;
    bool warned = false;
  };
  std::map<ClientId, PageRate> rates_;
  DriveInputs pending_;
  std::array<double, kMaxWaitingPushes> waiting_pushes_{};  ///< Headings, oldest first.
  std::size_t waiting_push_count_ = 0;
  Clock::time_point received_at_{};  ///< When the pending command arrived.
  std::optional<std::pair<ClientId, std::uint64_t>> acknowledgement_;
  std::function<void()> listener_;
  DriveStatistics statistics_;
};

}  // namespace upkie_rl
