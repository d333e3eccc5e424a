#include "envs/tasks/velocity_task.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>
#include "envs/core/shared_options.hpp"

namespace upkie_rl {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

}  // namespace

VelocityTask::VelocityTask(const RobotModel& model, const VelocityTaskConfig& config,
                           bool height_command)
    : config_(config),
      height_command_(height_command),
      observation_size_(make_observation_space(height_command, config.observe_command_acceleration,
                                               config.observe_acceleration)
                            .size()),
      legs_(model),
      wheels_(model.wheel_geometry()),
      imu_to_base_(model.rotation_base_to_imu()),
      reward_(config.reward) {
  if (config.relative_wheel_action && config.wheel_command_feedforward) {
    throw std::invalid_argument(
        "wheel_command_feedforward adds the command to absolute wheel targets: it needs "
        "relative_wheel_action false");
  }
  for (std::size_t i = 0; i < kNumServos; ++i) {
    const JointLimits& limits = model.servo_limits(i);
    effort_[i] = limits.effort;
    lower_limit_[i] = limits.lower;
    upper_limit_[i] = limits.upper;
  }
}

BoxSpace VelocityTask::make_observation_space(bool height_command, bool command_acceleration,
                                              bool imu_acceleration) {
  BoxSpace space;
  for (const std::size_t joint : kLegJoints) {
    space.add(std::string(kServoNames[joint]) + ".position", -kInf, kInf);
  }
  space.add("left_wheel.velocity", -kInf, kInf);
  space.add("right_wheel.velocity", -kInf, kInf);
  for (const char* axis : {"x", "y", "z"}) space.add(std::string("gravity.") + axis, -1.0f, 1.0f);
  for (const char* axis : {"x", "y", "z"}) space.add(std::string("gyro.") + axis, -kInf, kInf);
  for (const std::string_view joint : kServoNames) {
    space.add("last_action." + std::string(joint), -1.0f, 1.0f);
  }
  for (const char* column : kCommandColumns) space.add(column, -kInf, kInf);
  if (height_command) space.add(kHeightCommandColumn, -kInf, kInf);
  if (command_acceleration) {
    for (const char* column : kCommandAccelerationColumns) space.add(column, -kInf, kInf);
  }
  if (imu_acceleration) {
    for (const char* column : kImuAccelerationColumns) space.add(column, -kInf, kInf);
  }
  return space;
}

BoxSpace VelocityTask::make_action_space() {
  BoxSpace space;
  for (const std::string_view joint : kServoNames) space.add(std::string(joint), -1.0f, 1.0f);
  return space;
}

namespace {

/// Components that change sign under the left-right mirror, besides the servos'.
constexpr std::array<std::string_view, 6> kMirrorNegated = {
    "gravity.y",         "gyro.x", "gyro.z", "command.yaw_rate", "command.yaw_acceleration",
    "imu_acceleration.y"};

/// The mirror of `space` by its names (VelocityTask::make_mirror_symmetry).
SignedPermutation mirror_by_names(const BoxSpace& space, const std::string& what) {
  std::vector<std::size_t> source(space.size());
  std::vector<bool> negate(space.size(), false);
  for (std::size_t i = 0; i < space.size(); ++i) {
    const std::string& name = space.names[i];
    source[i] = i;
    std::string twin = name;
    if (const auto left = name.find("left_"); left != std::string::npos) {
      twin.replace(left, 5, "right_");
    } else if (const auto right = name.find("right_"); right != std::string::npos) {
      twin.replace(right, 6, "left_");
    }
    if (twin != name) {
      source[i] = space.index_of(twin);
      negate[i] = true;
    } else {
      negate[i] =
          std::find(kMirrorNegated.begin(), kMirrorNegated.end(), name) != kMirrorNegated.end();
    }
  }
  return SignedPermutation(std::move(source), std::move(negate), what);
}

}  // namespace

MirrorSymmetry VelocityTask::make_mirror_symmetry(const BoxSpace& observation,
                                                  const BoxSpace& action) {
  return {mirror_by_names(observation, "observation"), mirror_by_names(action, "action")};
}

void VelocityTask::servo_action(std::span<const float> action, const Observation& measured,
                                const VelocityCommand& command_followed,
                                ServoAction& commands) const {
  const std::array<double, kNumServos> leg_origin = leg_action_origin(command_followed);
  std::array<double, kNumServos> wheel_start{};
  if (config_.wheel_command_feedforward) {
    const WheelVelocities followed =
        wheels_.velocities(command_followed.forward_velocity, command_followed.yaw_rate);
    wheel_start[kLeftWheel] = followed.left;
    wheel_start[kRightWheel] = followed.right;
  } else if (config_.relative_wheel_action) {
    wheel_start[kLeftWheel] = measured.servo[kLeftWheel].velocity;
    wheel_start[kRightWheel] = measured.servo[kRightWheel].velocity;
  }
  for (std::size_t i = 0; i < kNumServos; ++i) {
    ServoCommand& command = commands[i];
    command.feedforward_torque = 0.0;
    command.maximum_torque = effort_[i];
    if (is_wheel(i)) {
      command.position = std::numeric_limits<double>::quiet_NaN();
      command.velocity = wheel_start[i] + config_.wheel_velocity_scale * action[i];
      command.kp_scale = 0.0;
      command.kd_scale = config_.wheel_kd_scale;
    } else {
      // Within the joint limits (a wide leg_action_scale spans more).
      command.position = std::clamp(leg_origin[i] + config_.leg_action_scale * action[i],
                                    lower_limit_[i], upper_limit_[i]);
      command.velocity = 0.0;
      command.kp_scale = config_.leg_kp_scale;
      command.kd_scale = config_.leg_kd_scale;
    }
  }
}

Eigen::Vector3d VelocityTask::gravity_in_base(const Observation& full) {
  return full.base_orientation.rotation_base_to_world.transpose() * Eigen::Vector3d(0, 0, -1);
}

double VelocityTask::tilt(const Observation& full) {
  return tilt_from_gravity(gravity_in_base(full));
}

double VelocityTask::floor_tilt(const Observation& full) {
  if (!full.has_sim) return tilt(full);
  return tilt_from_gravity(full.sim_base.orientation.conjugate() * Eigen::Vector3d(0, 0, -1));
}

BaseVelocity VelocityTask::measured_velocity(const Observation& full) {
  const Eigen::Matrix3d& rotation = full.base_orientation.rotation_base_to_world;
  BaseVelocity velocity;
  velocity.yaw_rate = (rotation * full.base_orientation.angular_velocity).z();
  if (!full.has_sim) {
    velocity.forward_velocity = full.wheel_odometry.velocity;
    return velocity;
  }
  Eigen::Vector3d heading(rotation(0, 0), rotation(1, 0), 0.0);
  const double norm = heading.norm();
  if (norm > 1e-9) heading /= norm;
  velocity.forward_velocity = heading.dot(full.sim_base.linear_velocity);
  return velocity;
}

std::array<double, 4> VelocityTask::leg_angles(const Observation& full) {
  std::array<double, 4> angles{};
  for (std::size_t k = 0; k < kLegJoints.size(); ++k) {
    angles[k] = full.servo[kLegJoints[k]].position;
  }
  return angles;
}

BaseVelocity VelocityTask::measure(const Observation& full) const {
  BaseVelocity measured = measured_velocity(full);
  measured.height =
      legs_.base_height(leg_angles(full), full.base_orientation.rotation_base_to_world);
  return measured;
}

std::array<double, 4> VelocityTask::leg_reference(const VelocityCommand& command) const {
  if (!height_command_) return {};  // straight legs
  return legs_.crouch_pose(command.height).leg_angles();
}

std::array<double, 4> leg_action_origin_angles(const LegKinematics& legs, bool about_crouch,
                                               double height) {
  if (!about_crouch) return {};  // straight legs
  return legs.crouch_pose(height).leg_angles();
}

std::array<double, kNumServos> VelocityTask::leg_action_origin(
    const VelocityCommand& command) const {
  std::array<double, kNumServos> origin{};
  if (!height_command_) return origin;  // straight legs
  const std::array<double, 4> angles =
      leg_action_origin_angles(legs_, config_.leg_action_about_crouch, command.height);
  for (std::size_t k = 0; k < kLegJoints.size(); ++k) origin[kLegJoints[k]] = angles[k];
  return origin;
}

std::array<double, 4> VelocityTask::leg_deviation(const Observation& full,
                                                  const VelocityCommand& command) const {
  const std::array<double, 4> reference = leg_reference(command);
  std::array<double, 4> deviation = leg_angles(full);
  for (std::size_t k = 0; k < deviation.size(); ++k) deviation[k] -= reference[k];
  return deviation;
}

void VelocityTask::write_observation(const Observation& full, std::span<const float> last_action,
                                     const VelocityCommand& command, std::span<float> observation,
                                     const VelocityCommand& command_rate) const {
  if (observation.size() != observation_size() || last_action.size() != kActionSize) {
    throw std::invalid_argument("VelocityTask: observation buffer has " +
                                std::to_string(observation.size()) + " components, expected " +
                                std::to_string(observation_size()));
  }
  std::size_t k = 0;
  for (const std::size_t joint : kLegJoints) {
    observation[k++] = static_cast<float>(full.servo[joint].position);
  }
  observation[k++] = static_cast<float>(full.servo[kLeftWheel].velocity);
  observation[k++] = static_cast<float>(full.servo[kRightWheel].velocity);
  const Eigen::Vector3d gravity = gravity_in_base(full);
  for (int i = 0; i < 3; ++i) observation[k++] = static_cast<float>(gravity[i]);
  for (int i = 0; i < 3; ++i) {
    observation[k++] = static_cast<float>(full.base_orientation.angular_velocity[i]);
  }
  for (const float u : last_action) observation[k++] = u;
  observation[k++] = static_cast<float>(command.forward_velocity);
  observation[k++] = static_cast<float>(command.yaw_rate);
  if (height_command_) observation[k++] = static_cast<float>(command.height);
  if (config_.observe_command_acceleration) {
    observation[k++] = static_cast<float>(command_rate.forward_velocity);
    observation[k++] = static_cast<float>(command_rate.yaw_rate);
  }
  if (config_.observe_acceleration) {
    const Eigen::Vector3d acceleration = imu_to_base_ * full.imu.linear_acceleration;
    for (int i = 0; i < 3; ++i) observation[k++] = static_cast<float>(acceleration[i]);
  }
}

StepResult VelocityTask::evaluate(const Observation& full, const VelocityCommand& command,
                                  std::span<const float> action,
                                  std::span<const float> previous_action) {
  VelocityRewardInputs inputs;
  inputs.command = command;
  inputs.velocity = height_command_ ? measure(full) : measured_velocity(full);
  inputs.track_height = height_command_;
  inputs.gravity_in_base = gravity_in_base(full);
  inputs.floor_tilt = floor_tilt(full);
  inputs.leg_deviation = leg_deviation(full, command);
  inputs.shin_tilt =
      largest_shin_tilt(pitch_from_gravity(inputs.gravity_in_base), leg_angles(full));
  inputs.action = action;
  inputs.previous_action = previous_action;
  StepResult result;
  result.reward = reward_(inputs);
  reason_ = VelocityTermination::kNone;
  if (tilt_from_gravity(inputs.gravity_in_base) > config_.fall_tilt) {
    reason_ = VelocityTermination::kTilt;
  } else if (config_.terminate_on_contact && full.floor_contact.non_wheel) {
    reason_ = VelocityTermination::kContact;
  }
  result.terminated = reason_ != VelocityTermination::kNone;
  return result;
}

void VelocityTaskConfig::declare_options(OptionTable& table) {
  table.add_real("wheel_velocity_scale", &wheel_velocity_scale, 1e-6, kOptionHuge,
                 "wheel velocity target at action 1 [rad/s] (with relative_wheel_action: the "
                 "change from the measured wheel velocity)");
  table.add_choice("relative_wheel_action", &relative_wheel_action,
                   {{"true", true}, {"false", false}},
                   "wheel velocity targets are the measured wheel velocity plus "
                   "wheel_velocity_scale times the action (a change of speed) rather than "
                   "wheel_velocity_scale times the action");
  table.add_choice("wheel_command_feedforward", &wheel_command_feedforward,
                   {{"true", true}, {"false", false}},
                   "absolute wheel targets add the followed command's wheel speeds (forward "
                   "velocity over the wheel radius, the yaw rate's differential)");
  table.add_real("leg_action_scale", &leg_action_scale, 1e-6, 10.0,
                 "hip and knee target offset from the default pose at action 1 [rad] (1.0: the "
                 "default crouch and room around it; 0.5 before the height command)");
  table.set_recorded_default("leg_action_scale", "0.5");
  table.add_choice("leg_action_about_crouch", &leg_action_about_crouch,
                   {{"true", true}, {"false", false}},
                   "hip and knee targets are offsets from the crouch pose of the followed "
                   "height command (its inverse kinematics) rather than from straight legs");
  table.add_choice("observe_command_acceleration", &observe_command_acceleration,
                   {{"true", true}, {"false", false}},
                   "append the followed command's forward and yaw accelerations over the "
                   "coming step to the observation (the ramp toward the target)");
  table.add_choice("observe_acceleration", &observe_acceleration,
                   {{"true", true}, {"false", false}},
                   "append the IMU's gravity-free linear acceleration in the base frame to the "
                   "observation (imu_acceleration.x, .y, .z [m/s^2])");
  table.add_real("leg_kp_scale", &leg_kp_scale, 0.0, ServosEnv::kMaxGainScale,
                 "kp_scale of hips and knees");
  table.add_real("leg_kd_scale", &leg_kd_scale, 0.0, ServosEnv::kMaxGainScale,
                 "kd_scale of hips and knees");
  table.add_real("wheel_kd_scale", &wheel_kd_scale, 0.0, ServosEnv::kMaxGainScale,
                 "kd_scale of the wheels' velocity loop");
  table.add_real("fall_tilt", &fall_tilt, 0.0, 3.2,
                 "terminate when the base tilts more than it [rad]");
  table.add_choice("terminate_on_contact", &terminate_on_contact,
                   {{"true", true}, {"false", false}},
                   "terminate when a part other than a wheel touches the floor");
  table.add_text("base_controller", &base_controller,
                 "residual mode: a controller spec (balancer:... from `rollout --controller "
                 "lqr`) whose action is added to residual_scale times the agent's");
  table.add_real("residual_scale", &residual_scale, 0.0, 1.0,
                 "residual mode: weight of the agent's action");
  table.add_real("residual_filter", &residual_filter, 0.0, 1.0,
                 "residual mode: time constant of a first-order filter on the agent's action "
                 "[s], kept wherever the policy runs; 0 for none");
  table.add_real("residual_fade_start", &residual_fade_start, 0.0, 1.6,
                 "residual mode: base tilt [rad] from which the agent's share fades");
  table.add_real("residual_fade_end", &residual_fade_end, 0.0, 1.6,
                 "residual mode: base tilt [rad] at which the agent's share has faded to none "
                 "(linearly from residual_fade_start); 0 for no fade");
  table.add_real("residual_leg_gain", &residual_leg_gain, 0.0, 10.0,
                 "residual mode: the agent's weight on hips and knees over its weight on the "
                 "wheels");
  reward.declare_options(table);
}

}  // namespace upkie_rl
