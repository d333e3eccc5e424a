#pragma once
/// @file
/// ServosEnv: the base environment of Upkie, commanding the six servos directly.

#include <array>
#include <memory>
#include <optional>
#include <random>

#include "envs/core/env.hpp"
#include "envs/randomization/action_lag.hpp"
#include "envs/randomization/init_randomization.hpp"
#include "envs/randomization/perturbation_settings.hpp"
#include "envs/randomization/push_schedule.hpp"
#include "envs/spaces/dict_space.hpp"
#include "model/robot_model.hpp"
#include "sim/physics_simulation.hpp"
#include "sim/simulation.hpp"

namespace upkie_rl {

/// Position NaN, velocity 0, feedforward 0, gain scales 1, maximum torque = effort: the
/// neutral servo commands (the zero controller of the servos environment).
ServoAction neutral_servo_action(const RobotModel& model);

/// The servos environment (environments.md section 2): typed ServoAction in, Observation
/// out, reward 0, never terminates.
///
/// Every command value is clamped to its bounds before it reaches the backend: position to
/// the joint limits (a NaN position passes: no position loop), velocity to the velocity
/// limit, feedforward torque to the effort, kp_scale and kd_scale to [0, kMaxGainScale],
/// maximum_torque to [0, effort].
///
/// As a flat Env: the action is 6 joints x 6 keys (kServoCommandFields), the observation 6
/// joints x 5 keys (kServoObservationFields), components named like `left_hip.position`;
/// NaN is legal in the position components only.
class ServosEnv final : public Env {
 public:
  /// Upper bound of kp_scale and kd_scale.
  static constexpr double kMaxGainScale = 5.0;

  /// @param simulation Backend, owned.
  /// @param model Robot description (joint limits).
  /// @param init_randomization Ranges of the initial state drawn at each reset.
  /// @param physics_steps_per_step Physics steps the backend runs per step (reporting only).
  /// @param perturbations Physical perturbations drawn at each reset (physics backends).
  /// @param action_lag Delay and lag between the commands sent and those applied (any
  ///        backend; see ActionLag).
  /// @throws std::invalid_argument on a null argument, inconsistent perturbations or lag
  ///         settings, or perturbations with a backend that is not a PhysicsSimulation.
  ServosEnv(std::unique_ptr<Simulation> simulation, std::shared_ptr<const RobotModel> model,
            const InitRandomization& init_randomization = {}, int physics_steps_per_step = 0,
            PerturbationSettings perturbations = {}, const ActionLagSettings& action_lag = {});

  /// Starts an episode; a seed re-seeds the generators the initial state and the
  /// perturbations are drawn from (two streams: the initial states do not depend on
  /// whether perturbations are on).
  const Observation& reset_servos(std::optional<std::uint64_t> seed);
  /// Starts an episode from `state` instead of a drawn one (identification replays a log from
  /// its measured states); the perturbations are drawn as reset_servos() draws them.
  /// @throws std::invalid_argument when `state` is not finite.
  const Observation& reset_servos_to(const ResetState& state, std::optional<std::uint64_t> seed);

  /// Clamps `action` to the bounds and holds it for one step, through the actuation's delay
  /// and lag (ActionLag), pushes included.
  /// @throws InvalidCommandError on a NaN velocity, torque or gain, or an infinite position,
  ///         when it is sent (not when it leaves the delay).
  const Observation& step_servos(const ServoAction& action);

  /// Pushes the base by hand (a browser's push in `upkie-rl drive`): `force_in_world` [N]
  /// on the base's centre of mass during the next `duration` seconds, added to the
  /// scheduled pushes. Returns false (nothing happens) on a backend without physics.
  /// @throws std::invalid_argument on a non-finite force or a duration not in (0, 10] s.
  bool push_base(const Eigen::Vector3d& force_in_world, double duration);

  /// The clamped version of `action` (what step_servos sends).
  void clamp_servo_action(const ServoAction& action, ServoAction& clamped) const;

  /// upkie_rl::neutral_servo_action() of this model.
  ServoAction neutral_servo_action() const { return upkie_rl::neutral_servo_action(*model_); }

  /// The action space as one Box per joint (keys kServoCommandFields).
  const DictSpace& action_dict_space() const { return action_dict_space_; }
  /// The observation space as one Box per joint (keys kServoObservationFields).
  const DictSpace& observation_dict_space() const { return observation_dict_space_; }

  const RobotModel& model() const { return *model_; }
  const std::shared_ptr<const RobotModel>& model_ptr() const { return model_; }

  // Env
  const BoxSpace& observation_space() const override { return observation_space_; }
  const BoxSpace& action_space() const override { return action_space_; }
  void reset(std::optional<std::uint64_t> seed, std::span<float> observation) override;
  StepResult step(std::span<const float> action, std::span<float> observation) override;
  const Observation* full_observation() const override { return &simulation_->observation(); }
  void neutral_action(std::span<float> action) const override;
  double timestep() const override { return simulation_->agent_timestep(); }
  int physics_steps_per_step() const override { return physics_steps_per_step_; }
  void set_randomization_scale(double scale) override;

 private:
  /// The perturbations of an episode, drawn (a seed re-seeds both generators).
  void start_perturbations(std::optional<std::uint64_t> seed);
  void write_observation(const Observation& full, std::span<float> observation) const;

  std::unique_ptr<Simulation> simulation_;
  std::shared_ptr<const RobotModel> model_;
  InitRandomization init_randomization_;
  int physics_steps_per_step_;
  PerturbationSettings perturbations_;
  PhysicsSimulation* physics_ = nullptr;  ///< simulation_ when it simulates physics.
  double randomization_scale_ = 1.0;
  std::mt19937_64 generator_{0};
  std::mt19937_64 perturbation_generator_{0};
  PushSchedule pushes_;
  std::optional<ActionLag> action_lag_;  ///< Set when its settings delay or lag anything.
  Eigen::Vector3d hand_push_force_ = Eigen::Vector3d::Zero();  ///< Of push_base [N].
  double hand_push_end_ = 0.0;  ///< Simulated time the hand push ends [s].
  DictSpace action_dict_space_;
  DictSpace observation_dict_space_;
  BoxSpace action_space_;
  BoxSpace observation_space_;
  std::array<std::size_t, kNumServos> position_indices_{};  // Where NaN is legal.
  ServoAction action_buffer_{};
  ServoAction clamped_buffer_{};
  std::array<float, kNumServos * 6> flat_buffer_{};
};

}  // namespace upkie_rl
