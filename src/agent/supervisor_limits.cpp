#include "agent/supervisor_limits.hpp"

#include <stdexcept>
#include <string>

#include "agent/agent_error.hpp"

namespace upkie_rl {

void SupervisorLimits::declare_options(OptionTable& table) {
  // The measured pitch is an arcsine, within +-pi/2: a bound of pi/2 could never trip.
  table.add_real("max_pitch", &max_pitch, 0.01, 1.5, "Attitude limit: |pitch| [rad]");
  // Beyond about pi/2 the robot lies on its side; same bound as the pitch.
  table.add_real("max_roll", &max_roll, 0.01, 1.5, "Attitude limit: |roll| [rad]");
  // 1 rad past the URDF limits (+-1.26 and +-2.51 rad on the legs) is past the mechanics.
  table.add_real("joint_position_margin", &joint_position_margin, 0.0, 1.0,
                 "Measured joint angle allowed beyond the joint's limits [rad]");
  // Three times the servos' velocity limits is beyond what they can reach.
  table.add_real("joint_velocity_factor", &joint_velocity_factor, 0.1, 3.0,
                 "Measured joint velocity allowed, as a fraction of the joint's limit");
  // At the top, 500 rad/s per 5 ms cycle: more than the wheels' 111 rad/s limit, so a
  // higher bound would mean the same (no rate limit).
  table.add_real("velocity_command_rate", &max_velocity_command_rate, 1.0, 1e5,
                 "Rate limit of velocity commands [rad/s^2]");
  // At the top, 5 rad per 5 ms cycle: more than a leg joint's whole range.
  table.add_real("position_command_rate", &max_position_command_rate, 0.1, 1000.0,
                 "Rate limit of position commands [rad/s]");
  // Above Upkie's largest effort (16 N.m) the cap is the effort anyway.
  table.add_real("max_torque", &max_torque, 0.0, 100.0,
                 "Cap of every command's maximum torque [N.m], never above the joint's effort "
                 "(0: the effort)");
  // A silent spine must be noticed within seconds.
  table.add_real("spine_timeout", &spine_timeout, 0.001, 10.0,
                 "The spine is silent after this long without an answer [s]");
  // 2000 cycles: 10 s at 200 Hz, as long as the longest spine timeout.
  table.add_integer("max_deadline_misses", &max_consecutive_deadline_misses, 1, 2000,
                    "Stop after this many missed deadlines in a row");
  // From 2 (a cycle of 1.5 periods is already a missed deadline) to 10 s at 200 Hz.
  table.add_real("max_cycle_periods", &max_cycle_periods, 2.0, 2000.0,
                 "Stop after one cycle longer than this many periods");
  // 200 cycles: 1 s at 200 Hz, 4 s at 50 Hz (the velocity task, the slowest), ample for the
  // wheels to come to rest; the bound keeps a stopping runner's exit within seconds.
  table.add_integer("stop_cycles", &nb_stop_cycles, 0, 200,
                    "Cycles of stop commands sent before the Stop request (200: 1 s at 200 Hz); "
                    "a second Ctrl-C or SIGTERM while stopping cuts them short");
}

void SupervisorLimits::validate() const {
  SupervisorLimits copy = *this;  // the table binds fields it could write; validate() reads
  OptionTable table;
  copy.declare_options(table);
  try {
    table.check([](const std::string& name) { return "supervisor limit " + name; },
                "supervisor limits");
  } catch (const std::invalid_argument& error) {
    throw AgentError(error.what());
  }
}

}  // namespace upkie_rl
