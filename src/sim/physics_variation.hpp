#pragma once
/// @file
/// PhysicsVariation: what differs from the nominal robot and world in one episode (domain
/// randomisation), set on a physics simulation before its reset.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <numbers>

#include "model/robot_model.hpp"
#include "sim/imu_uncertainty.hpp"

namespace upkie_rl {

/// Largest floor slope, about either axis [deg]: beyond it Upkie's tires (friction 1) still
/// hold, but a balancing policy meets slopes no real floor of its world has.
inline constexpr double kMaxSlopeDegrees = 15.0;
/// An angle in radians [rad] from degrees [deg] (the one conversion of the slopes).
constexpr double degrees_to_radians(double degrees) { return degrees * std::numbers::pi / 180.0; }

/// Largest payload on the base [kg], about half the robot's mass.
inline constexpr double kMaxPayloadMass = 3.0;
/// Largest payload offset from the base's centre of mass, along each axis [m].
inline constexpr double kMaxPayloadOffset = 0.2;

/// Physical parameters of one episode. The default is the nominal robot, bit for bit: a
/// simulation with the default variation gives the same trajectory as one never varied.
struct PhysicsVariation {
  /// Index of the base in mass_scale; servo s moves the body of index 1 + s.
  static constexpr std::size_t kBaseBody = 0;

  /// Factor on the mass and the principal inertias of each rigid body: the base, then the
  /// body each servo moves (links welded to a body by fixed joints share its factor).
  std::array<double, kNumServos + 1> mass_scale{1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0};
  /// Kinetic friction of each joint: torque -friction·sign(v) when |v| > 1e-3 rad/s [N.m].
  std::array<double, kNumServos> joint_friction{};
  /// Factor on each servo's feedback gains kp and kd (and its brake's damping): the real
  /// servos' gains differ from the simulated law's (another moteus configuration, a motor
  /// constant off its datasheet).
  std::array<double, kNumServos> servo_gain_scale{1.0, 1.0, 1.0, 1.0, 1.0, 1.0};
  /// Standard deviation of Gaussian noise added to each servo torque at every physics
  /// step (it is part of the torque the servo reports) [N.m].
  double torque_control_noise = 0.0;
  /// Standard deviation of Gaussian noise on the observed servo torques [N.m].
  double torque_measurement_noise = 0.0;
  /// Factor on the friction coefficient between the tires and the floor.
  double floor_friction_scale = 1.0;
  /// Factor on every servo's torque limit (its URDF effort): below 1, a weaker motor, a
  /// drained battery or a hot winding.
  double torque_limit_scale = 1.0;
  /// Floor slope about the robot's lateral axis at reset [rad], positive when it faces
  /// uphill. Simulated as a flat floor under tilted gravity (see FloorSlope).
  double slope_pitch = 0.0;
  /// Floor slope about the robot's forward axis at reset [rad], positive when the floor
  /// rises to its left (it drifts or tips to its right).
  double slope_roll = 0.0;
  /// Point mass rigidly attached to the base [kg], added to the base body's mass, centre
  /// of mass and inertia (after mass_scale, which does not scale it).
  double payload_mass = 0.0;
  /// Position of the payload from the base body's centre of mass, in the base frame (x
  /// forward, y left, z up) [m].
  Eigen::Vector3d payload_offset = Eigen::Vector3d::Zero();
  ImuUncertainty imu;
  /// Whether the world's floor bumps (PhysicsConfig::bumps) lie on the floor this episode;
  /// without them the floor is flat. Why: a policy trained for cable covers must also meet
  /// flat floors, and the bumps are geometry built once per simulation.
  bool floor_bumps = true;
  /// Seeds the noise drawn during the episode (torques, IMU).
  std::uint64_t noise_seed = 0;

  /// Whether the floor is tilted (gravity is, in the simulation).
  bool tilts_floor() const { return slope_pitch != 0.0 || slope_roll != 0.0; }
  /// Whether a payload is attached to the base.
  bool has_payload() const { return payload_mass != 0.0; }

  /// Whether the masses, the floor friction, the gravity or the floor's bumps differ from
  /// the nominal model.
  bool changes_model() const;

  /// @throws std::invalid_argument naming the first value out of its domain (scales must be
  ///         positive, frictions and deviations non-negative, slopes within
  ///         ±kMaxSlopeDegrees, the payload within kMaxPayloadMass and kMaxPayloadOffset,
  ///         everything finite).
  void validate() const;
};

/// The index in PhysicsVariation::mass_scale of a body of an engine's tree: 1 + the servo
/// that moves the nearest body up from `body` (itself included), or kBaseBody.
/// @param servo_bodies The body each servo moves.
/// @param parent_of    The parent of a body, -1 above the base.
template <class ParentOf>
std::size_t mass_scale_index(int body, const std::array<int, kNumServos>& servo_bodies,
                             ParentOf parent_of) {
  for (int ancestor = body; ancestor >= 0; ancestor = parent_of(ancestor)) {
    for (std::size_t servo = 0; servo < kNumServos; ++servo) {
      if (servo_bodies[servo] == ancestor) return 1 + servo;
    }
  }
  return PhysicsVariation::kBaseBody;
}

}  // namespace upkie_rl
