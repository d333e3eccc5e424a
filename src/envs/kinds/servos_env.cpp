#include "envs/kinds/servos_env.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "sim/base_observer.hpp"
#include "sim/observation_fields.hpp"
#include "sim/random_draws.hpp"
#include "sim/servo_command_fields.hpp"

namespace upkie_rl {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr std::size_t kActionKeys = kServoCommandFields.size();
constexpr std::size_t kObservationKeys = kServoObservationFields.size();
// position_indices_ marks the first component of each joint's row as its position.
static_assert(kServoCommandFields[0].member == &ServoCommand::position);

// Observation bounds of servo temperature [deg C] and voltage [V].
constexpr float kMaxTemperature = 100.0f;
constexpr float kMaxVoltage = 64.0f;

/// Bounds of one command field of a joint: the joint limits, and [0, kMaxGainScale] for the
/// gain scales.
std::pair<float, float> command_bounds(double ServoCommand::*member, const JointLimits& limits) {
  const auto velocity = static_cast<float>(limits.velocity);
  const auto effort = static_cast<float>(limits.effort);
  if (member == &ServoCommand::position) {
    if (!limits.has_position_limits()) return {-kInf, kInf};
    return {static_cast<float>(limits.lower), static_cast<float>(limits.upper)};
  }
  if (member == &ServoCommand::velocity) return {-velocity, velocity};
  if (member == &ServoCommand::feedforward_torque) return {-effort, effort};
  if (member == &ServoCommand::kp_scale || member == &ServoCommand::kd_scale) {
    return {0.0f, static_cast<float>(ServosEnv::kMaxGainScale)};
  }
  if (member == &ServoCommand::maximum_torque) return {0.0f, effort};
  throw std::logic_error("ServosEnv: no bounds for a servo command field");
}

/// Bounds of one measured field of a joint. Measured positions and velocities are not
/// bounded by the command limits: a joint overshoots its velocity limit after a position
/// step, and Bullet lets a joint rest up to 0.05 rad past a limit. The bounds are what can
/// be observed (Gymnasium checks it).
std::pair<float, float> observation_bounds(double ServoObservation::*member,
                                           const JointLimits& limits) {
  const auto effort = static_cast<float>(limits.effort);
  if (member == &ServoObservation::position || member == &ServoObservation::velocity) {
    return {-kInf, kInf};
  }
  if (member == &ServoObservation::torque) return {-effort, effort};
  if (member == &ServoObservation::temperature) return {0.0f, kMaxTemperature};
  if (member == &ServoObservation::voltage) return {0.0f, kMaxVoltage};
  throw std::logic_error("ServosEnv: no bounds for a servo observation field");
}

/// Stream of the perturbation generator, derived from a reset's seed.
constexpr std::uint64_t kPerturbationStream = 1;

}  // namespace

ServosEnv::ServosEnv(std::unique_ptr<Simulation> simulation,
                     std::shared_ptr<const RobotModel> model,
                     const InitRandomization& init_randomization, int physics_steps_per_step,
                     PerturbationSettings perturbations, const ActionLagSettings& action_lag)
    : simulation_(std::move(simulation)),
      model_(std::move(model)),
      init_randomization_(init_randomization),
      physics_steps_per_step_(physics_steps_per_step),
      perturbations_(std::move(perturbations)) {
  if (!simulation_) throw std::invalid_argument("ServosEnv: the simulation is null");
  if (!model_) throw std::invalid_argument("ServosEnv: the robot model is null");
  physics_ = dynamic_cast<PhysicsSimulation*>(simulation_.get());
  if (perturbations_.any() && physics_ == nullptr) {
    throw std::invalid_argument(
        "ServosEnv: perturbations need a physics backend (Bullet or MuJoCo)");
  }
  perturbations_.validate();
  if (action_lag.any()) action_lag_.emplace(action_lag, simulation_->agent_timestep());
  for (std::size_t i = 0; i < kNumServos; ++i) {
    const JointLimits& limits = model_->servo_limits(i);
    BoxSpace action;
    for (const ServoCommandField& field : kServoCommandFields) {
      const auto [lower, upper] = command_bounds(field.member, limits);
      action.add(std::string(field.key), lower, upper);
    }
    BoxSpace observation;
    for (const ServoObservationField& field : kServoObservationFields) {
      const auto [lower, upper] = observation_bounds(field.member, limits);
      observation.add(std::string(field.key), lower, upper);
    }
    const std::string joint(kServoNames[i]);
    action_dict_space_.entries.emplace_back(joint, std::move(action));
    observation_dict_space_.entries.emplace_back(joint, std::move(observation));
    position_indices_[i] = i * kActionKeys;
  }
  action_space_ = action_dict_space_.flatten();
  observation_space_ = observation_dict_space_.flatten();
}

void ServosEnv::start_perturbations(std::optional<std::uint64_t> seed) {
  hand_push_end_ = 0.0;  // the reset clears the simulation's base force
  if (seed) {
    generator_.seed(*seed);
    perturbation_generator_.seed(derive_seed(*seed, kPerturbationStream));
  }
  if (perturbations_.any()) {
    physics_->set_variation(perturbations_.sample(perturbation_generator_, randomization_scale_));
    pushes_.reset(perturbations_.push, randomization_scale_, perturbation_generator_());
  }
  if (action_lag_) action_lag_->reset(seed, randomization_scale_);
}

const Observation& ServosEnv::reset_servos(std::optional<std::uint64_t> seed) {
  start_perturbations(seed);
  return simulation_->reset(init_randomization_.scaled(randomization_scale_).sample(generator_));
}

const Observation& ServosEnv::reset_servos_to(const ResetState& state,
                                              std::optional<std::uint64_t> seed) {
  validate_reset_state(state);
  start_perturbations(seed);
  return simulation_->reset(state);
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
    const double yaw = base_yaw(last.base_orientation.rotation_base_to_world);
    Eigen::Vector3d force =
        perturbations_.push.enabled() ? pushes_.force(last.time, yaw) : Eigen::Vector3d::Zero();
    if (hand_push && last.time < hand_push_end_) force += hand_push_force_;
    // The step after the hand push clears its force; later steps skip this block.
    if (hand_push && last.time >= hand_push_end_) hand_push_end_ = 0.0;
    physics_->set_base_force(force);
  }
  if (!action_lag_) return simulation_->step(clamped_buffer_);
  // Refused when sent, not `delay` steps later when it would reach the servos.
  validate_servo_action(clamped_buffer_);
  return simulation_->step(action_lag_->apply(clamped_buffer_));
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
    for (std::size_t k = 0; k < kActionKeys; ++k) {
      row[k] = static_cast<float>(neutral[i].*kServoCommandFields[k].member);
    }
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
    for (std::size_t k = 0; k < kObservationKeys; ++k) {
      row[k] = static_cast<float>(servo.*kServoObservationFields[k].member);
    }
  }
}

void ServosEnv::reset(std::optional<std::uint64_t> seed, std::span<float> observation) {
  write_observation(reset_servos(seed), observation);
}

StepResult ServosEnv::step(std::span<const float> action, std::span<float> observation) {
  clamp_to_space(action_space_, action, flat_buffer_, position_indices_);
  for (std::size_t i = 0; i < kNumServos; ++i) {
    const float* row = flat_buffer_.data() + i * kActionKeys;
    for (std::size_t k = 0; k < kActionKeys; ++k) {
      action_buffer_[i].*kServoCommandFields[k].member = row[k];
    }
  }
  write_observation(step_servos(action_buffer_), observation);
  return StepResult{};
}

}  // namespace upkie_rl
