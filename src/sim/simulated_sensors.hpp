#pragma once
/// @file
/// SimulatedSensors: the observer pipeline every physics backend runs after its engine
/// steps (servos, base, IMU, wheel odometry, floor contact), engine-independent.

#include <cstdint>
#include <random>

#include "model/robot_model.hpp"
#include "sim/floor_slope.hpp"
#include "sim/imu_observer.hpp"
#include "sim/measured_state.hpp"
#include "sim/observation.hpp"
#include "sim/physics_config.hpp"
#include "sim/wheel_odometry_observer.hpp"

namespace upkie_rl {

/// Turns what an engine measures into an Observation. One per simulation.
class SimulatedSensors {
 public:
  SimulatedSensors(const RobotModel& model, const PhysicsConfig& config);

  /// Starts an episode: time 0, odometry origin at the measured wheel angles, IMU at rest.
  /// @throws SimulationDivergedError on a non-finite measurement.
  void reset(const MeasuredJoints& joints, const MeasuredBase& base, bool floor_contact,
             Observation& observation);

  /// Sets the IMU's bias and noise for the episode that the next reset starts, and seeds
  /// its noise.
  void set_imu_uncertainty(const ImuUncertainty& uncertainty, std::uint64_t noise_seed);

  /// Sets the floor's slope for the episode that the next reset starts. On a sloped floor
  /// the IMU and `base_orientation` measure relative to the tilted gravity, in the level
  /// frame, as a real IMU on a real slope does; `sim.base` stays in the engine's (floor)
  /// frame.
  void set_floor_slope(const FloorSlope& slope) { slope_ = slope; }

  /// Fills `observation` (whose time the caller advances) from the measurements.
  /// @throws SimulationDivergedError on a non-finite measurement, before writing anything.
  void observe(const MeasuredJoints& joints, const MeasuredBase& base, bool floor_contact,
               Observation& observation);

  /// Servo temperature and bus voltage reported in simulation.
  static constexpr double kTemperature = 42.0;  // [deg C]
  static constexpr double kVoltage = 18.0;      // [V]

 private:
  /// `level` is `base` in the level frame (see level_base), for the attitude.
  void observe_without_imu(const MeasuredJoints& joints, const MeasuredBase& base,
                           const MeasuredBase& level, bool floor_contact,
                           Observation& observation) const;

  void add_imu_uncertainty(Observation& observation);

  /// `base` in the level frame: itself on a flat floor, else rotated into `scratch`.
  const MeasuredBase& level_base(const MeasuredBase& base, MeasuredBase& scratch) const;

  ImuObserver imu_;
  WheelOdometryObserver odometry_;
  ImuUncertainty imu_uncertainty_;
  FloorSlope slope_;
  std::mt19937_64 imu_noise_{0};
};

}  // namespace upkie_rl
