#include "sim/mujoco_simulation.hpp"

#include <mujoco/mujoco.h>

#include <stdexcept>

#include "sim/tire_contact.hpp"

namespace upkie_rl {
namespace {

const MujocoConfig& validated(const MujocoConfig& config) {
  config.validate();
  return config;
}

}  // namespace

MujocoSimulation::MujocoSimulation(std::shared_ptr<const RobotModel> model,
                                   const MujocoConfig& config)
    : MujocoSimulation(model, config, build_mujoco_model(*model, validated(config))) {}

MujocoSimulation::MujocoSimulation(std::shared_ptr<const RobotModel> model,
                                   const MujocoConfig& config,
                                   std::shared_ptr<const MujocoModel> compiled)
    : PhysicsSimulation(*model, validated(config)),
      model_(std::move(model)),
      config_(config),
      compiled_(std::move(compiled)),
      episode_model_(compiled_->model.get()),
      data_(mj_makeData(compiled_->model.get())) {
  if (!data_) throw std::runtime_error("MuJoCo could not allocate its simulation data");
  reset(ResetState{});
}

MujocoSimulation::~MujocoSimulation() = default;

void MujocoSimulation::apply_model_variation() {
  const PhysicsVariation& variation = this->variation();
  const mjModel* nominal = compiled_->model.get();
  if (!variation.changes_model() && !config_.implicit_wheel_damping) {
    episode_model_ = nominal;
    return;
  }
  if (!varied_model_) {
    varied_model_.reset(mj_copyModel(nullptr, nominal));
    if (!varied_model_) throw std::runtime_error("MuJoCo could not copy the model");
  }
  mjModel* varied = varied_model_.get();
  episode_model_ = varied;
  const MujocoRobotIndex& index = compiled_->index;
  if (!variation.changes_model()) {
    // Undo an earlier episode's variation (same sizes: the copy allocates nothing); else
    // only the wheels' damping, which the steps rewrite, differs from the nominal model.
    if (holds_variation_) mj_copyModel(varied, nominal);
    holds_variation_ = false;
    for (const std::size_t wheel : {kLeftWheel, kRightWheel}) {
      const int dof = index.servo_dof[wheel];
      varied->dof_damping[dof] = nominal->dof_damping[dof];
    }
    return;
  }
  holds_variation_ = true;
  const auto parent_of = [nominal, &index](int body) {
    return body == index.root_body ? -1 : nominal->body_parentid[body];
  };
  for (int body = index.root_body; body < nominal->nbody; ++body) {
    const double scale = variation.mass_scale[mass_scale_index(body, index.servo_body, parent_of)];
    varied->body_mass[body] = scale * nominal->body_mass[body];
    for (int i = 0; i < 3; ++i) {
      varied->body_inertia[3 * body + i] = scale * nominal->body_inertia[3 * body + i];
    }
  }
  // The tires have contact priority: their friction is the contact's.
  for (const int tire : index.tire_geoms) {
    varied->geom_friction[3 * tire] =
        variation.floor_friction_scale * nominal->geom_friction[3 * tire];
  }
  mj_setConst(varied, data_.get());  // masses enter derived constants (subtree masses...)
}

const Observation& MujocoSimulation::reset(const ResetState& state) {
  validate_reset_state(state);
  apply_model_variation();
  const mjModel* m = episode_model_;
  mjData* d = data_.get();
  const MujocoRobotIndex& index = compiled_->index;
  mj_resetData(m, d);
  const Eigen::Quaterniond orientation = state.orientation_base_in_world.normalized();
  mjtNum* root = d->qpos + index.root_qpos;
  for (int i = 0; i < 3; ++i) root[i] = state.position_base_in_world[i];
  root[3] = orientation.w();
  root[4] = orientation.x();
  root[5] = orientation.y();
  root[6] = orientation.z();
  // Free joint velocity: the body origin's in the world frame, then angular in the body frame.
  mjtNum* root_velocity = d->qvel + index.root_dof;
  for (int i = 0; i < 3; ++i) {
    root_velocity[i] = state.linear_velocity_base_to_world_in_world[i];
    root_velocity[3 + i] = state.angular_velocity_base_in_base[i];
  }
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    d->qpos[index.servo_qpos[servo]] = state.joint_configuration[servo];
  }
  mj_forward(m, d);
  return observe_reset();
}

void MujocoSimulation::apply_servo_torques(const ServoAction& action, bool braked) {
  mjData* d = data_.get();
  const MujocoRobotIndex& index = compiled_->index;
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    const int dof = index.servo_dof[servo];
    const double velocity = d->qvel[dof];
    const double torque =
        joint_torque(servo, action[servo], braked, d->qpos[index.servo_qpos[servo]], velocity);
    d->qfrc_applied[dof] = torque;
    if (!config_.implicit_wheel_damping || !is_wheel(servo)) continue;
    // MuJoCo applies -damping·v with v taken at the end of the step (Euler's implicit
    // damping); adding damping·v now leaves the servo's torque, its damping implicit. Not
    // while the torque is at its limit, where the law does not depend on v.
    const ServoCommand& command = action[servo];
    const double limit = servo_torque_limit(command, model().servo_limits(servo).effort);
    const bool linear = !braked && std::abs(applied_torques_[servo]) < limit;
    const double damping = linear ? servo_gains().kd * command.kd_scale : 0.0;
    varied_model_->dof_damping[dof] = damping;
    d->qfrc_applied[dof] += damping * velocity;
  }
}

void MujocoSimulation::step_physics(const ServoAction& action, bool braked) {
  mjData* d = data_.get();
  const MujocoRobotIndex& index = compiled_->index;
  apply_servo_torques(action, braked);
  // xfrc_applied acts at the body's centre of mass, as Bullet's base force.
  for (int i = 0; i < 3; ++i) d->xfrc_applied[6 * index.root_body + i] = base_force()[i];
  mj_step(episode_model_, d);
}

void MujocoSimulation::measure(MeasuredJoints& joints, MeasuredBase& base) const {
  const mjData* d = data_.get();
  const MujocoRobotIndex& index = compiled_->index;
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    joints.position[servo] = d->qpos[index.servo_qpos[servo]];
    joints.velocity[servo] = d->qvel[index.servo_dof[servo]];
    joints.torque[servo] = applied_torques_[servo];
  }
  const mjtNum* root = d->qpos + index.root_qpos;
  const mjtNum* root_velocity = d->qvel + index.root_dof;
  const Eigen::Quaterniond orientation(root[3], root[4], root[5], root[6]);
  base.pose_in_world.setIdentity();
  // MuJoCo keeps the quaternion normalised; normalising again keeps a NaN a NaN.
  base.pose_in_world.linear() = orientation.normalized().toRotationMatrix();
  base.pose_in_world.translation() = Eigen::Vector3d(root[0], root[1], root[2]);
  base.linear_velocity_in_world =
      Eigen::Vector3d(root_velocity[0], root_velocity[1], root_velocity[2]);
  base.angular_velocity_in_world =
      base.pose_in_world.linear() *
      Eigen::Vector3d(root_velocity[3], root_velocity[4], root_velocity[5]);
}

namespace {

/// Whether a geom of the robot that is (`tires`) or is not (`!tires`) a tire is within
/// 1 mm of the floor or a bump on it (robot geoms collide with those only, never with each
/// other).
bool floor_contact(const mjData* d, const MujocoRobotIndex& index, bool tires) {
  if (index.floor_geom < 0) return false;
  for (int c = 0; c < d->ncon; ++c) {
    const mjContact& contact = d->contact[c];
    const int other = index.is_ground(contact.geom[0])   ? contact.geom[1]
                      : index.is_ground(contact.geom[1]) ? contact.geom[0]
                                                         : -1;
    if (other < 0 || contact.dist >= kTireContactDistance) continue;
    const bool tire = other == index.tire_geoms[0] || other == index.tire_geoms[1];
    if (tire == tires) return true;
  }
  return false;
}

}  // namespace

bool MujocoSimulation::tire_touches_floor() const {
  return floor_contact(data_.get(), compiled_->index, /*tires=*/true);
}

bool MujocoSimulation::non_tire_touches_floor() const {
  return floor_contact(data_.get(), compiled_->index, /*tires=*/false);
}

}  // namespace upkie_rl
