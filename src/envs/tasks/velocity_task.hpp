#pragma once
/// @file
/// VelocityTask: the logic of the velocity-tracking task (action mapping, observation,
/// reward, terminations) on the typed Observation, independent of the backend: the same
/// code runs on Bullet, MuJoCo and the spine of a real robot.

#include <array>
#include <span>
#include <string>

#include <Eigen/Core>

#include "envs/core/env.hpp"
#include "envs/spaces/box_space.hpp"
#include "envs/spaces/mirror_symmetry.hpp"
#include "envs/tasks/leg_kinematics.hpp"
#include "envs/tasks/velocity_command.hpp"
#include "envs/tasks/velocity_reward.hpp"
#include "model/robot_model.hpp"
#include "sim/observation.hpp"
#include "sim/servo_command.hpp"

namespace upkie_rl {

/// Settings of the task (environment options of the same names).
struct VelocityTaskConfig {
  double wheel_velocity_scale = 60.0;  ///< Wheel velocity target at |u| = 1 [rad/s].
  /// Wheel targets relative to the wheels' measured velocities: target = measured +
  /// wheel_velocity_scale·u, so that an action is a change of speed (about a torque) rather
  /// than the speed itself. Why: with absolute targets the velocity loop (kd 1 N.m.s/rad,
  /// 1.7 N.m) saturates beyond ±1.7 rad/s of error, ±0.03 of the action range at the
  /// default scale: a policy has to reproduce the wheels' own speed that precisely at every
  /// speed, and learned ones drifted and ran away above the speeds they were trained at.
  bool relative_wheel_action = false;
  /// Adds the followed command's wheel speeds (forward velocity / wheel radius, ± the yaw
  /// rate's differential) to absolute wheel targets, as the balancer's steady command does:
  /// an action of zero drives at the command and the policy adds what balance needs.
  bool wheel_command_feedforward = false;
  /// Hip or knee target offset at |u| = 1 [rad]. 1.0 (mjlab_upkie's scale): room for the
  /// crouch of the default height range (knees at -0.80 rad) and corrections around it;
  /// VelocityEnv refuses a height range whose crouch needs more. The policies trained
  /// before the height command used 0.5 (a checkpoint that does not name the option is
  /// read with 0.5).
  double leg_action_scale = 1.0;
  /// Hip and knee targets are offsets from the crouch pose of the followed height command
  /// (LegKinematics::crouch_pose, the inverse kinematics the baseline crouches with) rather
  /// than from straight legs: an action of zero holds the commanded height, open loop, and
  /// balance, wheels and the legs' corrections are left to the policy. Why: from straight
  /// legs, the crouch to 0.53 m needs hips and knees at 0.41 and -0.80 rad moved together;
  /// the policies of configs/velocity_scratch.yaml found a scissored half-crouch instead
  /// (one hip back, one forward, knees nearly straight) and stayed 7-14 mm above the
  /// command, where the baseline's kinematics track within 3 mm. Without a height command
  /// the origin is straight legs, as without the option.
  bool leg_action_about_crouch = false;
  /// Appends the followed command's forward and yaw accelerations over the coming step to
  /// the observation (VelocityCommandLimiter::rate): what the classical balancer feeds
  /// forward. Why: an MLP that sees only the followed command cannot tell that it ramps,
  /// and 82 % of a from-scratch policy's squared forward error fell in ramps and the second
  /// after them.
  bool observe_command_acceleration = false;
  /// Appends the IMU's gravity-free linear acceleration, in the base frame, to the
  /// observation (what Upkie's spine reports as imu.linear_acceleration). Why: a push shows
  /// there in the step it starts (30 N: about 9 m/s^2 at the IMU), while the velocities the
  /// policy sees move only as the push builds up. A trial policy told each step's push force
  /// (the simulation's truth) fell under none of the held-out 30 N pushes along the heading;
  /// observing this acceleration instead, with imu_accelerometer_noise 0.5 m/s^2 in
  /// training, five seeds of configs/velocity.yaml (which turns it on) fell there 2 times in
  /// 200 episodes against 15, but track a whole 20 ms step of action delay worse
  /// (docs/reality.md, "Today's config against the goals"). Off by default: the task's
  /// other configurations and their checkpoints keep their observations.
  bool observe_acceleration = false;
  double wheel_kd_scale = 1.0;  ///< Wheels: velocity loop only (kp unused).
  double leg_kp_scale = 2.0;
  double leg_kd_scale = 1.7;
  double fall_tilt = 1.22;           ///< Terminate when the base tilts more than this [rad] (70°).
  bool terminate_on_contact = true;  ///< Terminate when a non-wheel part touches the floor.
  /// Residual mode (VelocityEnv): a built-in controller spec ("balancer:..."), whose action
  /// is added to residual_scale times the agent's; empty for none.
  std::string base_controller;
  double residual_scale = 1.0;
  /// Residual mode: the agent's action passes a first-order filter of this time constant
  /// [s] wherever the policy runs (training, evaluations, the spine, the robot), 0 for none
  /// (ResidualLag). Part of the policy, like residual_scale: a policy trained with its
  /// corrections filtered chatters without the filter.
  double residual_filter = 0.0;
  /// Residual mode, training only: the agent's action passes a lag of time constant drawn
  /// in U(0, it) per episode [s] in place of residual_filter, 0 for none (ResidualLag; a
  /// randomisation option, which evaluations drop: they filter with residual_filter).
  double residual_lag_max = 0.0;
  /// Residual mode: the agent's share fades linearly from whole at a base tilt of
  /// residual_fade_start to none at residual_fade_end [rad] (the tilt from gravity, as the
  /// IMU measures it), leaving the base controller alone near the lean where the ankle
  /// brackets meet the floor; residual_fade_end 0 for no fade. Part of the policy. Trained
  /// with 0.25-0.35 rad on four seeds it did not end the falls under pushes along the
  /// heading that twice the PPO epochs bring (6 in 160 held-out episodes; docs/reality.md,
  /// "The residual faded with the lean"): off by default and in configs/velocity.yaml.
  double residual_fade_start = 0.0;
  double residual_fade_end = 0.0;
  /// Residual mode: the agent's share on the hips and knees is residual_leg_gain times its
  /// share on the wheels (residual_scale, faded). Part of the policy. At a residual of 0.3
  /// the legs move at most 0.15 rad from the base controller's; 3.33 gives them their whole
  /// range, which held every shipped world but the cable covers at 1 fall in 20 on two
  /// seeds of three but tracked 13.6-37.7 % better than the baseline (docs/reality.md, "A
  /// longer horizon, ..."): 1, the legs as the wheels, by default and in velocity.yaml.
  double residual_leg_gain = 1.0;
  VelocityRewardWeights reward;

  /// Declares the options of the fields, by their names, then the reward's.
  void declare_options(OptionTable& table);
};

/// Origin of the hip and knee targets (kLegJoints order) [rad] for a commanded base height
/// `height` [m]: its crouch pose when `about_crouch` (VelocityTaskConfig::
/// leg_action_about_crouch), straight legs (0) otherwise. The task's actions and the
/// balancer's both start from it.
std::array<double, 4> leg_action_origin_angles(const LegKinematics& legs, bool about_crouch,
                                               double height);

/// Why an episode of the velocity task ended.
enum class VelocityTermination { kNone = 0, kTilt, kContact };

/// "tilt", "contact" or "none".
constexpr const char* to_string(VelocityTermination reason) {
  switch (reason) {
    case VelocityTermination::kTilt:
      return "tilt";
    case VelocityTermination::kContact:
      return "contact";
    default:
      return "none";
  }
}

/// Action u in [-1, 1]^6 in the joint order (left hip, knee, wheel, right hip, knee, wheel):
/// hips and knees track position = origin + leg_action_scale·u, clamped to the joint
/// limits, where the origin is straight legs (0), or the crouch pose of the followed height
/// command with leg_action_about_crouch (leg_action_origin); wheels track
/// velocity = wheel_velocity_scale·u (joint convention: the right wheel turns backward
/// when the robot drives forward), or the measured wheel velocity plus that with
/// relative_wheel_action.
///
/// Observation (20, what the robot measures): 4 hip and knee angles [rad] (deviation from
/// the default pose), 2 wheel velocities [rad/s], the unit gravity vector in the base frame
/// (3, from the IMU's attitude), the base angular velocity in the base frame (3, the
/// gyroscope) [rad/s], the last action (6), the command (forward velocity [m/s], yaw rate
/// [rad/s]), then, with a height command (option height_command), the commanded base
/// height [m] (21 components), then, with observe_command_acceleration, the followed
/// command's forward [m/s²] and yaw [rad/s²] accelerations over the coming step (2 more),
/// then, with observe_acceleration, the IMU's gravity-free acceleration in the base frame
/// [m/s²] (3 more).
/// No base linear velocity: the robot does not measure it.
///
/// With a height command, the pose reward's reference is the crouch pose of the commanded
/// height (LegKinematics::crouch_pose) rather than straight legs, and the height is
/// tracked against LegKinematics::base_height of the measured leg angles and attitude.
class VelocityTask {
 public:
  static constexpr std::size_t kActionSize = kNumServos;
  /// Observation size without a height command.
  static constexpr std::size_t kObservationSize = 20;
  /// Observation size with a height command (and without the command's accelerations).
  static constexpr std::size_t kHeightObservationSize = kObservationSize + 1;
  /// Observation size with a height command, the command's accelerations and the IMU's
  /// acceleration: the largest.
  static constexpr std::size_t kMaxObservationSize = kObservationSize + 1 + 2 + 3;
  /// Index of the command's forward velocity in the observation (yaw rate next).
  static constexpr std::size_t kCommandIndex = 18;
  /// Index of the commanded base height in an observation with a height command.
  static constexpr std::size_t kHeightCommandIndex = 20;
  /// Hip and knee joints, in the order of the observation.
  static constexpr std::array<std::size_t, 4> kLegJoints = {kLeftHip, kLeftKnee, kRightHip,
                                                            kRightKnee};

  /// @param height_command Whether the command has a base height (observed, rewarded).
  VelocityTask(const RobotModel& model, const VelocityTaskConfig& config, bool height_command);

  /// The observation space: the commanded height when `height_command`, then the command's
  /// accelerations when `command_acceleration`, then the IMU's acceleration when
  /// `imu_acceleration`.
  static BoxSpace make_observation_space(bool height_command, bool command_acceleration = false,
                                         bool imu_acceleration = false);
  static BoxSpace make_action_space();
  /// The left-right mirror (y -> -y) of these spaces, by their component names: each left
  /// servo's component swaps with its right twin's, negated (the right joints' angles and
  /// velocities mirror the left's); gravity's y, the gyroscope's x and z (a pseudovector),
  /// the yaw command and its acceleration, and the IMU acceleration's y change sign; the
  /// rest (pitch, forward velocity, height) is unchanged. tests/envs/mirror_symmetry_test.cpp
  /// checks it against the physics: a mirrored action from a symmetric start gives the mirrored
  /// observations.
  static MirrorSymmetry make_mirror_symmetry(const BoxSpace& observation, const BoxSpace& action);

  /// The servo commands of the normalised action `action` (already clamped to [-1, 1]);
  /// `measured` is the last observation, whose wheel velocities a relative wheel action
  /// (VelocityTaskConfig::relative_wheel_action) starts from; `command` the followed
  /// command of a wheel feedforward (VelocityTaskConfig::wheel_command_feedforward).
  void servo_action(std::span<const float> action, const Observation& measured,
                    const VelocityCommand& command, ServoAction& commands) const;

  /// Writes the observation of `full` with the last action and the command to follow;
  /// `command_rate` (VelocityCommandLimiter::rate) is read with observe_command_acceleration.
  void write_observation(const Observation& full, std::span<const float> last_action,
                         const VelocityCommand& command, std::span<float> observation,
                         const VelocityCommand& command_rate = {}) const;

  /// Reward (terms in reward().terms()) and termination of a step that held `command`,
  /// applied `action` after `previous_action` and led to `full`.
  StepResult evaluate(const Observation& full, const VelocityCommand& command,
                      std::span<const float> action, std::span<const float> previous_action);

  /// Forward velocity and yaw rate of the base: ground truth in simulation (the base's
  /// velocity along its heading, the world-vertical angular velocity), wheel odometry and
  /// gyroscope on a real robot.
  static BaseVelocity measured_velocity(const Observation& full);
  /// measured_velocity with the base height of the legs' kinematics
  /// (LegKinematics::base_height).
  BaseVelocity measure(const Observation& full) const;
  /// Unit gravity vector in the base frame.
  static Eigen::Vector3d gravity_in_base(const Observation& full);
  /// Angle between the base's vertical and the world's [rad].
  static double tilt(const Observation& full);
  /// Angle between the base's vertical and the floor's normal [rad]: from the simulation's
  /// ground truth, whose world is the floor's (a slope tilts gravity, not the floor); tilt()
  /// without it.
  static double floor_tilt(const Observation& full);

  VelocityTermination termination_reason() const { return reason_; }
  const VelocityReward& reward() const { return reward_; }
  const VelocityTaskConfig& config() const { return config_; }
  bool height_command() const { return height_command_; }
  /// The size of this task's observation space (make_observation_space of its options).
  std::size_t observation_size() const { return observation_size_; }
  const LegKinematics& legs() const { return legs_; }

  /// Origin of each servo's position target [rad] under the followed command `command`:
  /// the crouch pose of its height with leg_action_about_crouch and a height command, 0
  /// otherwise (and for the wheels).
  std::array<double, kNumServos> leg_action_origin(const VelocityCommand& command) const;

 private:
  /// Hip and knee angles (kLegJoints order) of the crouch pose of `command`'s height with a
  /// height command, straight legs (0) without.
  std::array<double, 4> leg_reference(const VelocityCommand& command) const;
  /// Hip and knee angles of `full` in kLegJoints order [rad].
  static std::array<double, 4> leg_angles(const Observation& full);
  /// The leg angles' deviations from the pose reward's reference for `command`.
  std::array<double, 4> leg_deviation(const Observation& full,
                                      const VelocityCommand& command) const;

  VelocityTaskConfig config_;
  bool height_command_;
  std::size_t observation_size_;
  LegKinematics legs_;
  std::array<double, kNumServos> lower_limit_{};
  std::array<double, kNumServos> upper_limit_{};
  std::array<double, kNumServos> effort_{};
  WheelGeometry wheels_;
  /// Maps the IMU's vectors into the base frame (RobotModel::rotation_base_to_imu).
  Eigen::Matrix3d imu_to_base_;
  VelocityReward reward_;
  VelocityTermination reason_ = VelocityTermination::kNone;
};

}  // namespace upkie_rl
