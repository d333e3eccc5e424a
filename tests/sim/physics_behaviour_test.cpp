/// The behaviour every physics backend must show, run on Bullet and on MuJoCo. Where the
/// engines differ, the tolerance says by how much and why.

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>

#include "sim/physics_backends.hpp"
#include "sim/servo_actions.hpp"

namespace upkie_rl {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::shared_ptr<const RobotModel> model() { return RobotModel::default_model(); }

/// One backend under test.
struct Backend {
  const char* name;
  std::function<std::unique_ptr<PhysicsSimulation>(const PhysicsConfig&)> make;
  /// Past its limit, how far a joint pushed at full effort may go [rad]: Bullet's split
  /// impulse leaves penetrations under 0.04 uncorrected; MuJoCo's limits are soft
  /// constraints (time constant two physics steps) that a knee hitting its limit at about
  /// 20 rad/s passes by 0.064 rad for a few milliseconds before resting within 0.01.
  double joint_limit_overshoot;
};

using testing::make_bullet;
using testing::make_mujoco;

using testing::limp_action;
using testing::pendulum_action;

class PhysicsBehaviour : public ::testing::TestWithParam<Backend> {
 protected:
  std::unique_ptr<PhysicsSimulation> make(const PhysicsConfig& config = {}) const {
    return GetParam().make(config);
  }
};

TEST_P(PhysicsBehaviour, FreeFallWithoutFloor) {
  PhysicsConfig config;
  config.floor = false;
  config.nb_substeps = 1;
  auto simulation = make(config);
  const double z0 = simulation->observation().sim_base.position.z();
  for (int step = 0; step < 50; ++step) simulation->step(limp_action());
  const double duration = 0.05;
  // Semi-implicit Euler falls v*dt further than the exact parabola after n steps
  // (0.5 g dt^2 n), i.e. 0.25 mm here.
  EXPECT_NEAR(simulation->observation().sim_base.position.z() - z0,
              -0.5 * config.gravity * duration * duration, 1e-3);
  EXPECT_NEAR(simulation->observation().time, duration, 1e-12);
}

TEST_P(PhysicsBehaviour, AccelerometerReadsTheMeanAccelerationOfEachStep) {
  // Falling freely, the IMU accelerates at g whatever the number of physics steps between
  // two observations: the raw accelerometer reads zero and the gravity-free one g downward,
  // but for Bullet's multibody damping (0.03 m/s^2 after 50 ms of fall). Dividing a step's
  // velocity change by one physics step read nb_substeps times g (49 m/s^2 at 5).
  for (const int substeps : {1, 5}) {
    PhysicsConfig config;
    config.floor = false;
    config.nb_substeps = substeps;
    auto simulation = make(config);
    for (int step = 0; step < 10; ++step) simulation->step(limp_action());
    const ImuObservation& imu = simulation->observation().imu;
    EXPECT_LT(imu.raw_linear_acceleration.norm(), 0.05) << substeps << " substeps";
    EXPECT_NEAR(imu.linear_acceleration.norm(), config.gravity, 0.05) << substeps << " substeps";
  }
}

TEST_P(PhysicsBehaviour, ResetStateIsObserved) {
  auto simulation = make();
  const Observation& observation = simulation->observation();
  EXPECT_TRUE(observation.sim_base.position.isApprox(Eigen::Vector3d(0, 0, 0.6), 1e-12));
  EXPECT_NEAR(observation.base_orientation.pitch, 0.0, 1e-12);
  EXPECT_EQ(observation.wheel_odometry.position, 0.0);
  EXPECT_FALSE(observation.floor_contact.contact);  // tires start 43 mm above the floor
  EXPECT_DOUBLE_EQ(observation.servo[kLeftHip].temperature, 42.0);
  EXPECT_DOUBLE_EQ(observation.servo[kLeftHip].voltage, 18.0);
  // Upright, at rest: the accelerometer reads +g upward, i.e. -g along the IMU's z (down).
  EXPECT_TRUE(observation.imu.raw_linear_acceleration.isApprox(Eigen::Vector3d(0, 0, -9.81), 1e-9));

  ResetState state;
  state.position_base_in_world = Eigen::Vector3d(1.0, 2.0, 0.7);
  state.orientation_base_in_world = Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitY());
  state.angular_velocity_base_in_base = Eigen::Vector3d(0.0, 0.5, 0.0);
  state.linear_velocity_base_to_world_in_world = Eigen::Vector3d(0.3, 0.0, 0.0);
  state.joint_configuration[kLeftHip] = 0.3;
  simulation->reset(state);
  EXPECT_TRUE(observation.sim_base.position.isApprox(state.position_base_in_world, 1e-12));
  EXPECT_NEAR(observation.base_orientation.pitch, 0.2, 1e-12);
  EXPECT_NEAR(observation.base_orientation.angular_velocity.y(), 0.5, 1e-12);
  EXPECT_NEAR(observation.sim_base.linear_velocity.x(), 0.3, 1e-12);
  EXPECT_NEAR(observation.servo[kLeftHip].position, 0.3, 1e-12);
  EXPECT_EQ(observation.time, 0.0);
}

TEST_P(PhysicsBehaviour, LandsOnWheelsWithFloorContact) {
  auto simulation = make();
  const double radius = simulation->model().wheel_radius();
  for (int step = 0; step < 40; ++step) simulation->step(pendulum_action(0.0, radius));
  EXPECT_TRUE(simulation->observation().floor_contact.contact);
  // Standing on straight legs the base is about 0.557 m above the floor; the soft tires
  // sink by about m g / k = 0.9 mm.
  EXPECT_NEAR(simulation->observation().sim_base.position.z(), 0.557, 5e-3);
}

/// Time [s] a limp robot released upright with yaw `yaw` takes to pitch past 1 rad.
double limp_fall_time(PhysicsSimulation& simulation, double yaw) {
  ResetState state;
  state.orientation_base_in_world = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ());
  simulation.reset(state);
  while (simulation.observation().time < 5.0) {
    simulation.step(limp_action());
    if (std::abs(simulation.observation().base_orientation.pitch) > 1.0) break;
  }
  return simulation.observation().time;
}

TEST_P(PhysicsBehaviour, LimpRobotFallsInAboutOneSecond) {
  // Released upright, the limp robot folds and tips over: the reference PyBullet robot
  // passes 1 rad of pitch after about 1.1 s. The fall starts from numerical asymmetry and
  // the legs' collapse, so the engines agree on the order, not the millisecond.
  auto simulation = make();
  for (double yaw : {0.0, M_PI / 2.0}) {
    const double fall_time = limp_fall_time(*simulation, yaw);
    EXPECT_GT(fall_time, 0.2) << "yaw " << yaw;
    EXPECT_LT(fall_time, 2.0) << "yaw " << yaw;
  }
}

TEST_P(PhysicsBehaviour, FeedforwardTorqueIsReported) {
  auto simulation = make();
  ServoAction action = limp_action();
  action[kLeftKnee].feedforward_torque = 0.42;
  simulation->step(action);
  EXPECT_NEAR(simulation->observation().servo[kLeftKnee].torque, 0.42, 1e-12);
  EXPECT_NEAR(simulation->observation().servo[kRightKnee].torque, 0.0, 1e-12);
}

TEST_P(PhysicsBehaviour, ServoGainsCanBeReplaced) {
  PhysicsConfig config;
  config.nb_substeps = 1;  // the reported torque is the law's at the reset state
  auto simulation = make(config);
  ServoAction action = limp_action();
  action[kLeftKnee].position = 0.1;
  action[kLeftKnee].kp_scale = 1.0;
  const auto knee_torque = [&] {
    simulation->reset(ResetState{});
    return simulation->step(action).servo[kLeftKnee].torque;
  };
  EXPECT_NEAR(knee_torque(), 20.0 * 0.1, 1e-12);
  simulation->set_servo_gains(ServoGains{5.0, 0.5});
  EXPECT_DOUBLE_EQ(simulation->servo_gains().kd, 0.5);
  EXPECT_NEAR(knee_torque(), 5.0 * 0.1, 1e-12);
  EXPECT_THROW(simulation->set_servo_gains(ServoGains{-1.0, 1.0}), std::invalid_argument);
  EXPECT_THROW(simulation->set_servo_gains(ServoGains{1.0, kNaN}), std::invalid_argument);
  EXPECT_DOUBLE_EQ(simulation->servo_gains().kp, 5.0);  // a refused change changes nothing
}

TEST_P(PhysicsBehaviour, WheelInTheAirReachesCommandedVelocity) {
  // A free wheel has spin inertia I = 2.6e-4 kg.m^2: the servo law evaluated every 1 ms has
  // loop gain kd*kd_scale*dt/I, stable below 2. At kd_scale 1 (gain 3.8) a wheel in the air
  // oscillates in a +-1.7 N.m limit cycle, as in the reference (same law, inertia and
  // step); on the floor the robot's mass (m r^2 ~ 0.013 kg.m^2) makes it stable.
  PhysicsConfig config;
  config.floor = false;
  auto simulation = make(config);
  ServoAction action = pendulum_action(0.0, 0.05);
  action[kLeftWheel].velocity = 5.0;
  action[kRightWheel].velocity = -3.0;
  action[kLeftWheel].kd_scale = 0.25;
  action[kRightWheel].kd_scale = 0.25;
  for (int step = 0; step < 40; ++step) simulation->step(action);
  EXPECT_NEAR(simulation->observation().servo[kLeftWheel].velocity, 5.0, 0.05);
  EXPECT_NEAR(simulation->observation().servo[kRightWheel].velocity, -3.0, 0.05);
}

TEST_P(PhysicsBehaviour, JointLimitsHold) {
  PhysicsConfig config;
  config.floor = false;
  auto simulation = make(config);
  for (std::size_t servo : {kLeftHip, kLeftKnee, kRightHip, kRightKnee}) {
    for (double torque : {-16.0, 16.0}) {
      simulation->reset(ResetState{});
      ServoAction action = limp_action();
      action[servo].feedforward_torque = torque;
      double extreme = 0.0;
      for (int step = 0; step < 100; ++step) {
        simulation->step(action);
        extreme = std::max(extreme, std::abs(simulation->observation().servo[servo].position));
      }
      const double limit = model()->servo_limits(servo).upper;
      EXPECT_GT(extreme, limit - 0.01) << kServoNames[servo] << " " << torque;
      EXPECT_LT(extreme, limit + GetParam().joint_limit_overshoot)
          << kServoNames[servo] << " " << torque;
    }
  }
}

/// Runs v = 10 theta + 1 p + 0.1 p_dot at 200 Hz, returns the largest |pitch| seen.
double run_pendulum_law(PhysicsSimulation& simulation, double duration, double gain_scale) {
  const double radius = simulation.model().wheel_radius();
  double max_pitch = 0.0;
  const int steps = static_cast<int>(duration / simulation.agent_timestep());
  for (int step = 0; step < steps; ++step) {
    const Observation& observation = simulation.observation();
    const double velocity = gain_scale * (10.0 * observation.base_orientation.pitch +
                                          1.0 * observation.wheel_odometry.position +
                                          0.1 * observation.wheel_odometry.velocity);
    simulation.step(pendulum_action(std::clamp(velocity, -1.0, 1.0), radius));
    max_pitch = std::max(max_pitch, std::abs(simulation.observation().base_orientation.pitch));
  }
  return max_pitch;
}

TEST_P(PhysicsBehaviour, PendulumLawBalancesForTenSeconds) {
  auto simulation = make();
  EXPECT_LT(run_pendulum_law(*simulation, 10.0, 1.0), 0.3);
}

TEST_P(PhysicsBehaviour, WithoutBalanceControlItFallsWithinThreeSeconds) {
  auto simulation = make();
  EXPECT_GT(run_pendulum_law(*simulation, 3.0, 0.0), 1.0);
}

TEST_P(PhysicsBehaviour, UrdfInertiaSourceAlsoBalances) {
  PhysicsConfig config;
  config.inertia_source = InertiaSource::kUrdf;
  auto simulation = make(config);
  EXPECT_LT(run_pendulum_law(*simulation, 2.0, 1.0), 0.3);
}

TEST_P(PhysicsBehaviour, SameCommandsSameTrajectory) {
  auto first = make();
  auto second = make();
  ServoAction action = limp_action();
  action[kLeftWheel].feedforward_torque = 0.3;
  for (int step = 0; step < 100; ++step) {
    first->step(action);
    second->step(action);
  }
  EXPECT_EQ(first->observation().sim_base.position, second->observation().sim_base.position);
  // Reset starts from the same engine state: the replay is identical too.
  const Eigen::Vector3d end = first->observation().sim_base.position;
  first->reset(ResetState{});
  for (int step = 0; step < 100; ++step) first->step(action);
  EXPECT_EQ(first->observation().sim_base.position, end);
}

TEST_P(PhysicsBehaviour, NonFiniteCommandsAreRefused) {
  auto simulation = make();
  ServoAction action{};
  action[kLeftWheel].velocity = kNaN;
  EXPECT_THROW(simulation->step(action), InvalidCommandError);
  action[kLeftWheel].velocity = 0.0;
  action[kRightHip].feedforward_torque = INFINITY;
  EXPECT_THROW(simulation->step(action), InvalidCommandError);
  action[kRightHip].feedforward_torque = 0.0;
  action[kRightHip].kd_scale = kNaN;
  EXPECT_THROW(simulation->step(action), InvalidCommandError);
  EXPECT_EQ(simulation->observation().time, 0.0);  // nothing was stepped
}

TEST_P(PhysicsBehaviour, NonFiniteStateIsDetectedNotPropagated) {
  auto simulation = make();
  ResetState state;
  state.linear_velocity_base_to_world_in_world = Eigen::Vector3d(1e308, 0.0, 0.0);
  simulation->reset(state);
  EXPECT_THROW(
      {
        for (int step = 0; step < 10; ++step) simulation->step(limp_action());
      },
      SimulationDivergedError);
  EXPECT_THROW(simulation->step(limp_action()), SimulationDivergedError);
  simulation->reset(ResetState{});
  EXPECT_NO_THROW(simulation->step(limp_action()));
  EXPECT_TRUE(simulation->observation().sim_base.position.allFinite());
}

TEST_P(PhysicsBehaviour, NonFiniteResetStateIsRefused) {
  auto simulation = make();
  ResetState state;
  state.joint_configuration[kLeftKnee] = kNaN;
  EXPECT_THROW(simulation->reset(state), std::invalid_argument);
  state.joint_configuration[kLeftKnee] = 0.0;
  state.orientation_base_in_world.coeffs().setZero();
  EXPECT_THROW(simulation->reset(state), std::invalid_argument);
}

TEST_P(PhysicsBehaviour, BadConfigIsRefused) {
  PhysicsConfig config;
  config.nb_substeps = 0;
  EXPECT_THROW(make(config), std::invalid_argument);
  config.nb_substeps = 5;
  config.physics_timestep = -1e-3;
  EXPECT_THROW(make(config), std::invalid_argument);
  config.physics_timestep = 1e-3;
  config.servo_gains.kp = -1.0;
  EXPECT_THROW(make(config), std::invalid_argument);
}

INSTANTIATE_TEST_SUITE_P(Engines, PhysicsBehaviour,
                         ::testing::Values(Backend{"Bullet", make_bullet, 0.06},
                                           Backend{"MuJoCo", make_mujoco, 0.07}),
                         [](const ::testing::TestParamInfo<Backend>& info) {
                           return std::string(info.param.name);
                         });

}  // namespace
}  // namespace upkie_rl
