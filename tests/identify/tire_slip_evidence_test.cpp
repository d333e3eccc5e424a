// Tire slip told from the accelerometer against the wheels' rolling, and replays started
// off it.

#include "identify/tire_slip_evidence.hpp"

#include <gtest/gtest.h>

#include <iostream>
#include <numeric>
#include <vector>

#include "common/temp_files.hpp"
#include "identify/excitation_log.hpp"
#include "identify/log_replay.hpp"
#include "identify/measured_reset_state.hpp"
#include "sim/physics_config.hpp"

namespace upkie_rl {
namespace {

/// 10 s of the excitation on Bullet's floor of friction 0.6, where its tires slip at times.
const RobotLog& slippery_log() {
  static const RobotLog log = [] {
    const auto path = testing::temp_path("slippery.mpack");
    ExcitationSettings excitation;
    excitation.duration = 10.0;
    excitation.seed = 1;
    write_excitation_log("Upkie-Bullet-Servos", {{"floor_friction", "0.6"}}, excitation, path);
    return read_robot_log(path);
  }();
  return log;
}

std::vector<std::size_t> every_cycle(const RobotLog& log) {
  std::vector<std::size_t> cycles(log.cycles.size());
  std::iota(cycles.begin(), cycles.end(), 0);
  return cycles;
}

// The simulation's true base velocity (in the log, never read by identification) says where
// the no-slip start state is off: the evidence, from measurements only, is small where the
// tires roll and large where they slipped.
TEST(TireSlipEvidence, SmallWhileRollingLargeAfterSlip) {
  const RobotLog& log = slippery_log();
  ASSERT_TRUE(logs_accelerometer(log));
  const std::shared_ptr<const RobotModel> model = RobotModel::default_model();
  const std::vector<std::size_t> cycles = every_cycle(log);
  const std::vector<double> evidence =
      tire_slip_evidence(*model, log, cycles, 0.02, PhysicsConfig{}.gravity);
  ASSERT_EQ(evidence.size(), cycles.size());
  std::size_t rolling = 0, rolling_quiet = 0, slipping = 0, slipping_flagged = 0;
  for (std::size_t i = 0; i < cycles.size(); ++i) {
    const Observation& observation = log.cycles[i].observation;
    ASSERT_TRUE(observation.has_sim);
    const double slip =
        (observation.sim_base.linear_velocity -
         measured_reset_state(*model, observation).linear_velocity_base_to_world_in_world)
            .head<2>()
            .norm();
    if (slip < 0.005) {
      ++rolling;
      rolling_quiet += evidence[i] <= 0.02 ? 1 : 0;
    } else if (slip > 0.05) {
      ++slipping;
      slipping_flagged += evidence[i] > 0.02 ? 1 : 0;
    }
  }
  std::cout << rolling_quiet << " of " << rolling << " rolling cycles under 2 cm/s, "
            << slipping_flagged << " of " << slipping << " slipping ones over" << std::endl;
  ASSERT_GT(slipping, 0u) << "the log should slip somewhere";
  EXPECT_GT(rolling_quiet, 0.9 * static_cast<double>(rolling));      // 94 % here
  EXPECT_GT(slipping_flagged, 0.7 * static_cast<double>(slipping));  // 84 % here
}

// Replays moved off slip predict the log better at its own physics; with the threshold at
// 0, or a log without an accelerometer, the starts stay where they were.
TEST(TireSlipEvidence, ReplaysStartOffSlip) {
  const RobotLog& log = slippery_log();
  const EnvOptions physics = {{"floor_friction", "0.6"}};
  ReplaySettings settings;
  const LogReplay moved("Upkie-Bullet-Servos", physics, log, settings, 0, 0.0);
  settings.slip_threshold = 0.0;
  const LogReplay fixed("Upkie-Bullet-Servos", physics, log, settings, 0, 0.0);
  EXPECT_GT(moved.num_windows_moved_off_slip(), 0u);
  EXPECT_EQ(fixed.num_windows_moved_off_slip(), 0u);
  EXPECT_EQ(moved.num_windows(), fixed.num_windows());
  const double moved_rmse = moved.rmse({});
  const double fixed_rmse = fixed.rmse({});
  std::cout << "rmse at the log's physics: " << moved_rmse << " off slip, " << fixed_rmse
            << " at fixed starts" << std::endl;
  EXPECT_LT(moved_rmse, fixed_rmse);

  RobotLog without = log;
  for (LoggedCycle& cycle : without.cycles) cycle.observation.imu.raw_linear_acceleration.setZero();
  EXPECT_FALSE(logs_accelerometer(without));
  const LogReplay blind("Upkie-Bullet-Servos", physics, without, ReplaySettings{}, 0, 0.0);
  EXPECT_EQ(blind.num_windows_moved_off_slip(), 0u);
}

}  // namespace
}  // namespace upkie_rl
