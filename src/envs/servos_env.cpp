#include "envs/servos_env.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sim/random_draws.hpp"

namespace upkie_rl {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr std::size_t kActionKeys = kServoActionKeys.size();
constexpr std::size_t kObservationKeys = kServoObservationKeys.size();

// Observation bounds of servo temperature [deg C] and voltage [V].
constexpr float kMaxTemperature = 100.0f;
constexpr float kMaxVoltage = 64.0f;

/// Stream of the perturbation generator, derived from a reset's seed.
constexpr std::uint64_t kPerturbationStream = 1;

}  // namespace

ServosEnv::ServosEnv(std::unique_ptr<Simulation> simulation,
                     std::shared_ptr<const RobotModel> model,
                     const InitRandomization& init_randomization, int physics_steps_per_step,
                     const PerturbationSettings& perturbations)
    : simulation_(std::move(simulation)),
      model_(std::move(model)),
      init_randomization_(init_randomization),
      physics_steps_per_step_(physics_steps_per_step),
      perturbations_(perturbations) {
  if (!simulation_) throw std::invalid_argument("ServosEnv: the simulation is null");
  if (!model_) throw std::invalid_argument("ServosEnv: the robot model is null");
  physics_ = dynamic_cast<PhysicsSimulation*>(simulation_.get());
  if (perturbations_.any() && physics_ == nullptr) {
    throw std::invalid_argument(
        "ServosEnv: perturbations need a physics backend (Bullet or MuJoCo)");
  }
  perturbations_.validate();
  const float gain = static_cast<float>(kMaxGainScale);
  for (std::size_t i = 0; i < kNumServos; ++i) {
    const JointLimits& limits = model_->servo_limits(i);
    const float lower = limits.has_position_limits() ? static_cast<float>(limits.lower) : -kInf;
    const float upper = limits.has_position_limits() ? static_cast<float>(limits.upper) : kInf;
    const auto velocity = static_cast<float>(limits.velocity);
    const auto effort = static_cast<float>(limits.effort);
    BoxSpace action;
    action.add(kServoActionKeys[0], lower, upper);
    action.add(kServoActionKeys[1], -velocity, velocity);
    action.add(kServoActionKeys[2], -effort, effort);
    action.add(kServoActionKeys[3], 0.0f, gain);
    action.add(kServoActionKeys[4], 0.0f, gain);
    action.add(kServoActionKeys[5], 0.0f, effort);
    // Measured positions and velocities are not bounded by the command limits: a joint
    // overshoots its velocity limit after a position step, and Bullet lets a joint rest up to
    // 0.05 rad past a limit. The bounds are what can be observed (Gymnasium checks it).
    BoxSpace observation;
    observation.add(kServoObservationKeys[0], -kInf, kInf);
    observation.add(kServoObservationKeys[1], -kInf, kInf);
    observation.add(kServoObservationKeys[2], -effort, effort);
    observation.add(kServoObservationKeys[3], 0.0f, kMaxTemperature);
    observation.add(kServoObservationKeys[4], 0.0f, kMaxVoltage);
    const std::string joint(kServoNames[i]);
    action_dict_space_.entries.emplace_back(joint, std::move(action));
    observation_dict_space_.entries.emplace_back(joint, std::move(observation));
    position_indices_[i] = i * kActionKeys;
  }
  action_space_ = action_dict_space_.flatten();
  observation_space_ = observation_dict_space_.flatten();
}

const Observation& ServosEnv::reset_servos(std::optional<std::uint64_t> seed) {
  hand_push_end_ = 0.0;  // the reset clears the simulation's base force
  if (seed) {
    generator_.seed(*seed);
    perturbation_generator_.seed(derive_seed(*seed, kPerturbationStream));
  }
  if (perturbations_.any()) {
    physics_->set_variation(perturbations_.sample(perturbation_generator_, randomization_scale_));
    pushes_.reset(perturbations_.push, randomization_scale_, perturbation_generator_());
  }
  return simulation_->reset(init_randomization_.scaled(randomization_scale_).sample(generator_));
}

void ServosEnv::set_randomization_scale(double scale) {
  check_randomization_scale(scale);
  randomization_scale_ = scale;
}

void ServosEnv::clamp_servo_action(const ServoAction& action, ServoAction& clamped) const {
  for (std::size_t i = 0; i < kNumServos; ++i) {
    const JointLimits& limits = model_->servo_limits(i);
    const ServoCommand& in = action[i];
    ServoCommand& out = clamped[i];
    if (std::isinf(in.position)) {
      throw InvalidCommandError(std::string(kServoNames[i]) +
                                ".position is infinite (NaN disables the position loop)");
    }
    // std::clamp keeps NaN, which is how a NaN position (and a NaN elsewhere, for the
    // backend to reject with the joint's name) passes through.
    out.position = limits.has_position_limits()
                       ? std::clamp(in.position, limits.lower, limits.upper)
                       : in.position;
    out.velocity = std::clamp(in.velocity, -limits.velocity, limits.velocity);
    out.feedforward_torque = std::clamp(in.feedforward_torque, -limits.effort, limits.effort);
    out.kp_scale = std::clamp(in.kp_scale, 0.0, kMaxGainScale);
    out.kd_scale = std::clamp(in.kd_scale, 0.0, kMaxGainScale);
    out.maximum_torque = std::clamp(in.maximum_torque, 0.0, limits.effort);
  }
}

bool ServosEnv::push_base(const Eigen::Vector3d& force_in_world, double duration) {
  if (!force_in_world.allFinite())
    throw std::invalid_argument("push_base: the force is not finite");
  if (!(duration > 0.0 && duration <= 10.0)) {
    throw std::invalid_argument("push_base: the duration must be in (0, 10] s");
  }
  if (physics_ == nullptr) return false;
  hand_push_force_ = force_in_world;
  hand_push_end_ = simulation_->observation().time + duration;
  return true;
}

const Observation& ServosEnv::step_servos(const ServoAction& action) {
  clamp_servo_action(action, clamped_buffer_);
  const Observation& last = simulation_->observation();
  const bool hand_push = hand_push_end_ > 0.0;
  if (perturbations_.push.enabled() || hand_push) {
    const Eigen::Matrix3d& rotation = last.base_orientation.rotation_base_to_world;
    const double yaw = std::atan2(rotation(1, 0), rotation(0, 0));
    Eigen::Vector3d force =
        perturbations_.push.enabled() ? pushes_.force(last.time, yaw) : Eigen::Vector3d::Zero();
    if (hand_push && last.time < hand_push_end_) force += hand_push_force_;
    // The step after the hand push clears its force; later steps skip this block.
    if (hand_push && last.time >= hand_push_end_) hand_push_end_ = 0.0;
    physics_->set_base_force(force);
  }
  return simulation_->step(clamped_buffer_);
}

ServoAction neutral_servo_action(const RobotModel& model) {
  ServoAction action{};
  for (std::size_t i = 0; i < kNumServos; ++i) {
    action[i].position = std::numeric_limits<double>::quiet_NaN();
    action[i].velocity = 0.0;
    action[i].feedforward_torque = 0.0;
    action[i].kp_scale = 1.0;
    action[i].kd_scale = 1.0;
    action[i].maximum_torque = model.servo_limits(i).effort;
  }
  return action;
}

void ServosEnv::neutral_action(std::span<float> action) const {
  const ServoAction neutral = neutral_servo_action();
  for (std::size_t i = 0; i < kNumServos; ++i) {
    float* row = action.data() + i * kActionKeys;
    row[0] = static_cast<float>(neutral[i].position);
    row[1] = static_cast<float>(neutral[i].velocity);
    row[2] = static_cast<float>(neutral[i].feedforward_torque);
    row[3] = static_cast<float>(neutral[i].kp_scale);
    row[4] = static_cast<float>(neutral[i].kd_scale);
    row[5] = static_cast<float>(neutral[i].maximum_torque);
  }
}

void ServosEnv::write_observation(const Observation& full, std::span<float> observation) const {
  if (observation.size() != observation_space_.size()) {
    throw std::invalid_argument("ServosEnv: observation buffer has " +
                                std::to_string(observation.size()) + " components, expected " +
                                std::to_string(observation_space_.size()));
  }
  for (std::size_t i = 0; i < kNumServos; ++i) {
    const ServoObservation& servo = full.servo[i];
    float* row = observation.data() + i * kObservationKeys;
    row[0] = static_cast<float>(servo.position);
    row[1] = static_cast<float>(servo.velocity);
    row[2] = static_cast<float>(servo.torque);
    row[3] = static_cast<float>(servo.temperature);
    row[4] = static_cast<float>(servo.voltage);
  }
}

void ServosEnv::reset(std::optional<std::uint64_t> seed, std::span<float> observation) {
  write_observation(reset_servos(seed), observation);
}

StepResult ServosEnv::step(std::span<const float> action, std::span<float> observation) {
  clamp_to_space(action_space_, action, flat_buffer_, position_indices_);
  for (std::size_t i = 0; i < kNumServos; ++i) {
    const float* row = flat_buffer_.data() + i * kActionKeys;
    action_buffer_[i] = ServoCommand{row[0], row[1], row[2], row[3], row[4], row[5]};
  }
  write_observation(step_servos(action_buffer_), observation);
  return StepResult{};
}

}  // namespace upkie_rl
