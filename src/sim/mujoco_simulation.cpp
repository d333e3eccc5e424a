#include "sim/mujoco_simulation.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cstddef>
#include <stdexcept>

#include "model/robot_model.hpp"
#include "sim/mass_properties.hpp"
#include "sim/tire_contact.hpp"

namespace upkie_rl {
namespace {

/// Rolling speed below which the rolling resistance grows in proportion [rad/s]: at
/// 0.1 rad/s (5 mm/s on the ground) its slope, 0.01 m x 26 N / 0.1 rad/s = 2.6 N.m.s/rad
/// per wheel, against the robot's inertia seen by a wheel (m r² ≈ 0.013 kg.m²), gives
/// 0.2 per 1 ms step: well inside explicit stability (2).
constexpr double kRollingSpeedScale = 0.1;

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
  if (!data_) throw ModelError("MuJoCo could not allocate its simulation data");
  reset(ResetState{});
}

MujocoSimulation::~MujocoSimulation() = default;

namespace {

/// The mass properties of body `body` of `model` (its inertial frame in its body frame).
MassProperties body_mass_properties(const mjModel* model, int body) {
  MassProperties properties;
  properties.mass = model->body_mass[body];
  const mjtNum* quat = model->body_iquat + 4 * body;
  properties.principal_frame.linear() =
      Eigen::Quaterniond(quat[0], quat[1], quat[2], quat[3]).normalized().toRotationMatrix();
  for (int i = 0; i < 3; ++i) {
    properties.principal_frame.translation()[i] = model->body_ipos[3 * body + i];
    properties.principal_inertia[i] = model->body_inertia[3 * body + i];
  }
  return properties;
}

void set_body_mass_properties(mjModel* model, int body, const MassProperties& properties) {
  model->body_mass[body] = properties.mass;
  const Eigen::Quaterniond rotation(properties.principal_frame.linear());
  const double quat[4] = {rotation.w(), rotation.x(), rotation.y(), rotation.z()};
  for (int i = 0; i < 4; ++i) model->body_iquat[4 * body + i] = quat[i];
  for (int i = 0; i < 3; ++i) {
    model->body_ipos[3 * body + i] = properties.principal_frame.translation()[i];
    model->body_inertia[3 * body + i] = properties.principal_inertia[i];
  }
}

/// How far an episode without floor bumps sinks them under the floor [m]: out of the
/// robot's reach (geoms of the world body, the floor included, never collide together).
constexpr double kBumpSinkDepth = 10.0;

/// Writes `variation` into `varied`, a copy of `nominal`: masses and inertias scaled, the
/// payload on the base, the tires' friction, `gravity` and the floor's bumps.
void vary_model(mjModel* varied, const mjModel* nominal, const MujocoRobotIndex& index,
                const PhysicsVariation& variation, const Eigen::Vector3d& gravity) {
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
  // The base's inertial frame, which an earlier episode's payload may have moved.
  const int root = index.root_body;
  for (int i = 0; i < 3; ++i) varied->body_ipos[3 * root + i] = nominal->body_ipos[3 * root + i];
  for (int i = 0; i < 4; ++i) varied->body_iquat[4 * root + i] = nominal->body_iquat[4 * root + i];
  if (variation.has_payload()) {
    const MassProperties base = body_mass_properties(varied, root);
    set_body_mass_properties(
        varied, root,
        with_point_mass(base, variation.payload_mass,
                        base.principal_frame.translation() + variation.payload_offset));
  }
  // The tires have contact priority: their friction is the contact's.
  for (const int tire : index.tire_geoms) {
    varied->geom_friction[3 * tire] =
        variation.floor_friction_scale * nominal->geom_friction[3 * tire];
  }
  for (int i = 0; i < 3; ++i) varied->opt.gravity[i] = gravity[i];
  // An episode without the bumps sinks them under the floor, out of reach and out of view.
  const double bump_sink = variation.floor_bumps ? 0.0 : kBumpSinkDepth;
  for (int geom = index.first_bump_geom; geom < index.first_bump_geom + index.num_bump_geoms;
       ++geom) {
    const std::ptrdiff_t height = 3 * static_cast<std::ptrdiff_t>(geom) + 2;
    varied->geom_pos[height] = nominal->geom_pos[height] - bump_sink;
  }
}

}  // namespace

void MujocoSimulation::apply_model_variation(const Eigen::Vector3d& gravity) {
  const PhysicsVariation& variation = this->variation();
  const mjModel* nominal = compiled_->model.get();
  if (!variation.changes_model() && !config_.implicit_wheel_damping) {
    episode_model_ = nominal;
    return;
  }
  if (!varied_model_) {
    varied_model_.reset(mj_copyModel(nullptr, nominal));
    if (!varied_model_) throw ModelError("MuJoCo could not copy the model");
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
  vary_model(varied, nominal, index, variation, gravity);
  mj_setConst(varied, data_.get());  // masses enter derived constants (subtree masses...)
}

const Observation& MujocoSimulation::reset(const ResetState& state) {
  validate_reset_state(state);
  apply_model_variation(start_floor_slope(state));
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
    d->qvel[index.servo_dof[servo]] = state.joint_velocities[servo];
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
    const double limit = servo_torque_limit(command, torque_limit(servo));
    const bool linear = !braked && std::abs(applied_torques_[servo]) < limit;
    const double damping = linear ? servo_gains(servo).kd * command.kd_scale : 0.0;
    varied_model_->dof_damping[dof] = damping;
    d->qfrc_applied[dof] += damping * velocity;
  }
}

void MujocoSimulation::apply_rolling_resistance() {
  if (!config_.tire_rolling_resistance || config_.tire_condim == 6) return;
  const mjModel* m = episode_model_;
  mjData* d = data_.get();
  const MujocoRobotIndex& index = compiled_->index;
  for (std::size_t side = 0; side < 2; ++side) {
    const int geom = index.tire_geoms[side];
    const int body = m->geom_bodyid[geom];
    // The normal force the tire carries, summed over its contacts of the last step.
    double normal_force = 0.0;
    for (int i = 0; i < d->ncon; ++i) {
      const mjContact& contact = d->contact[i];
      if ((contact.geom1 != geom && contact.geom2 != geom) || contact.exclude != 0) continue;
      mjtNum force[6];
      mj_contactForce(m, d, i, force);
      normal_force += std::max(0.0, force[0]);
    }
    // A torque against the wheel's rolling (its angular velocity about its axis, relative
    // to the static floor), up to rolling_friction [m] x the normal force, as Bullet's
    // rolling friction constraint; saturated linearly below kRollingSpeedScale so that it
    // stays smooth and stable when evaluated once per step.
    const int joint = m->dof_jntid[index.servo_dof[side == 0 ? kLeftWheel : kRightWheel]];
    const mjtNum* axis = d->xaxis + 3 * joint;
    const mjtNum* angular_velocity = d->cvel + 6 * body;
    const double rolling = mju_dot3(angular_velocity, axis);
    const double limit = m->geom_friction[3 * geom + 2] * normal_force;
    const double torque = -limit * std::clamp(rolling / kRollingSpeedScale, -1.0, 1.0);
    for (int i = 0; i < 3; ++i) d->xfrc_applied[6 * body + 3 + i] = torque * axis[i];
  }
}

void MujocoSimulation::step_physics(const ServoAction& action, bool braked) {
  mjData* d = data_.get();
  const MujocoRobotIndex& index = compiled_->index;
  apply_servo_torques(action, braked);
  apply_rolling_resistance();
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

RobotMassDistribution MujocoSimulation::mass_distribution() const {
  const mjModel* m = episode_model_;
  mjData* d = data_.get();
  // The body positions of the current joint positions. A step recomputes them from qpos
  // before anything else, and nothing reads them between steps: the trajectory is unchanged.
  mj_kinematics(m, d);
  const int root = compiled_->index.root_body;
  RobotMassDistribution distribution;
  distribution.base = body_mass_properties(m, root);
  Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
  for (int body = root; body < m->nbody; ++body) {
    distribution.total_mass += m->body_mass[body];
    weighted += m->body_mass[body] *
                Eigen::Vector3d(d->xipos[3 * body], d->xipos[3 * body + 1], d->xipos[3 * body + 2]);
  }
  distribution.center_of_mass = weighted / distribution.total_mass;
  return distribution;
}

bool MujocoSimulation::tire_touches_floor() const {
  return floor_contact(data_.get(), compiled_->index, /*tires=*/true);
}

bool MujocoSimulation::non_tire_touches_floor() const {
  return floor_contact(data_.get(), compiled_->index, /*tires=*/false);
}

}  // namespace upkie_rl
