#pragma once
/// @file
/// Spine logs: the mpacklog format (a stream of MessagePack dictionaries, one per spine
/// cycle) that Upkie's spines write and the `mpacklog` Python package reads, and that
/// `upkie-rl spine --log` writes too, so that a simulated run and a robot run look alike.

#include <cstdint>
#include <vector>

#include "base/error.hpp"
#include "sim/observation.hpp"
#include "sim/servo_command.hpp"

namespace upkie_rl {

/// A log that cannot be read or used: truncated, malformed, missing a key or a column,
/// holding a NaN or an impossible value, or sampled at an irregular rate. The message is one
/// line naming the file and the problem.
class RobotLogError : public Error {
 public:
  using Error::Error;
};

/// The keys of one spine log dictionary (Upkie's Spine::log_working_dict): the persistent
/// action dictionary, the observation dictionary (docs/spine.md), the spine's own state
/// (read past), and the time of the observation [s].
inline constexpr const char* kSpineLogActionKey = "action";
inline constexpr const char* kSpineLogObservationKey = "observation";
inline constexpr const char* kSpineLogSpineKey = "spine";
inline constexpr const char* kSpineLogTimeKey = "time";

/// Largest spine log read [bytes]: a 1 kHz cycle dictionary is about 3 kB, so 2 GiB hold
/// about ten minutes of a robot's spine, more than an identification needs.
inline constexpr std::uintmax_t kMaxSpineLogBytes = std::uintmax_t{2} << 30;

/// Largest magnitude a logged measurement may have: joint angles, rates and torques of a
/// real robot are far below it, so a larger value (1e308) is a corrupt record.
inline constexpr double kMaxLoggedMagnitude = 1e6;

/// One logged cycle: what the spine measured and the servo commands in force.
struct LoggedCycle {
  double time = 0.0;  ///< [s]
  Observation observation;
  ServoAction command{};
};

}  // namespace upkie_rl
