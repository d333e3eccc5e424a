#include "sim/bullet_simulation.hpp"

#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointLimitConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>
#include <btBulletDynamicsCommon.h>

#include <cmath>
#include <string>
#include <vector>

#include "sim/mass_properties.hpp"
#include "sim/tire_contact.hpp"

namespace upkie_rl {
namespace {

/// Sides of the convex hull Bullet's URDF importer builds for a cylinder.
constexpr int kCylinderHullSides = 32;

/// Linear and angular damping of every link (btMultiBody default, kept by PyBullet).
constexpr double kLinkDamping = 0.04;

btVector3 to_bullet(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
Eigen::Vector3d to_eigen(const btVector3& v) { return {v.x(), v.y(), v.z()}; }
btQuaternion to_bullet(const Eigen::Quaterniond& q) { return {q.x(), q.y(), q.z(), q.w()}; }
Eigen::Quaterniond to_eigen(const btQuaternion& q) { return {q.w(), q.x(), q.y(), q.z()}; }
btTransform to_bullet(const Eigen::Isometry3d& pose) {
  return btTransform(to_bullet(Eigen::Quaterniond(pose.linear())), to_bullet(pose.translation()));
}

std::unique_ptr<btCollisionShape> make_shape(const CollisionShape& shape) {
  if (shape.kind == CollisionShape::Kind::kBox) {
    auto box = std::make_unique<btBoxShape>(to_bullet(Eigen::Vector3d(shape.box_size / 2.0)));
    box->setMargin(kCollisionMargin);
    return box;
  }
  // As Bullet's URDF importer does: a 32-gon prism hull with a 1 mm margin.
  auto hull = std::make_unique<btConvexHullShape>();
  for (int i = 0; i < kCylinderHullSides; ++i) {
    const double angle = 2.0 * M_PI * i / kCylinderHullSides;
    const double x = shape.radius * std::sin(angle);
    const double y = shape.radius * std::cos(angle);
    hull->addPoint(btVector3(x, y, shape.length / 2.0), false);
    hull->addPoint(btVector3(x, y, -shape.length / 2.0), false);
  }
  hull->setMargin(kCollisionMargin);
  hull->recalcLocalAabb();
  return hull;
}

/// Why: Bullet's default pools hold 4096 contact manifolds and 4096 collision algorithms
/// (megabytes at double precision), laid out again at every reset, which was 4.9 % of an
/// identification's time (it resets the world at each 0.2 s replay: perf, 60 s log). The
/// robot on a floor with bumps uses a few dozen of each; a pool that runs out falls back to
/// the heap, so only where the memory comes from changes, never the physics.
btDefaultCollisionConstructionInfo robot_sized_pools() {
  btDefaultCollisionConstructionInfo info;
  info.m_defaultMaxPersistentManifoldPoolSize = 256;
  info.m_defaultMaxCollisionAlgorithmPoolSize = 256;
  return info;
}

}  // namespace

/// Everything Bullet owns for one episode. Rebuilt at each reset.
struct BulletWorld {
  btDefaultCollisionConfiguration collision_configuration{robot_sized_pools()};
  btCollisionDispatcher dispatcher{&collision_configuration};
  btDbvtBroadphase broadphase;
  btMultiBodyConstraintSolver solver;
  btMultiBodyDynamicsWorld world{&dispatcher, &broadphase, &solver, &collision_configuration};
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::unique_ptr<btMultiBody> multibody;
  std::vector<std::unique_ptr<btMultiBodyLinkCollider>> colliders;
  std::vector<std::unique_ptr<btMultiBodyJointLimitConstraint>> joint_limits;
  std::unique_ptr<btDefaultMotionState> ground_motion_state;
  std::unique_ptr<btRigidBody> ground;
  /// The bumps across the floor: one static body, a compound of a box or convex hull per
  /// bump (null without bumps).
  std::unique_ptr<btDefaultMotionState> bumps_motion_state;
  std::unique_ptr<btRigidBody> bumps;
  std::array<int, kNumServos> servo_link{};  ///< Multibody link index of each servo.
  std::array<const btCollisionObject*, 2> tires{};
  /// Pose of the root body's principal (COM) frame in the base link frame.
  Eigen::Isometry3d base_com_in_base = Eigen::Isometry3d::Identity();

  BulletWorld() = default;
  BulletWorld(const BulletWorld&) = delete;
  BulletWorld& operator=(const BulletWorld&) = delete;

  ~BulletWorld() {
    // The world refers to everything below: take it all out before it is destroyed.
    for (auto& limit : joint_limits) world.removeMultiBodyConstraint(limit.get());
    for (auto& collider : colliders) world.removeCollisionObject(collider.get());
    if (multibody) world.removeMultiBody(multibody.get());
    if (ground) world.removeRigidBody(ground.get());
    if (bumps) world.removeRigidBody(bumps.get());
  }

  /// Whether `object` is the ground or the bumps on it: what a robot part touches.
  bool is_ground(const btCollisionObject* object) const {
    return object != nullptr && (object == ground.get() || object == bumps.get());
  }
};

namespace {

void configure_solver(btMultiBodyDynamicsWorld& world, const Eigen::Vector3d& gravity) {
  world.setGravity(to_bullet(gravity));
  // Bullet physics-server defaults, which PyBullet and the reference simulation use.
  btContactSolverInfo& info = world.getSolverInfo();
  info.m_numIterations = 50;
  info.m_erp2 = 0.08;
  info.m_frictionERP = 0.2;
  info.m_linearSlop = 1e-5;
  info.m_warmstartingFactor = 0.1;
  info.m_leastSquaresResidualThreshold = 1e-7;
  info.m_splitImpulse = 1;
  info.m_restitution = 0.0;
  info.m_solverMode |= SOLVER_USE_2_FRICTION_DIRECTIONS;
}

void add_ground(BulletWorld& bullet, double friction_scale) {
  // A fixed box 200 x 200 x 10 m with its top face at z = 0, lateral friction 1 (Bullet
  // multiplies the frictions of the two bodies in contact, so this scales the tires').
  auto box = std::make_unique<btBoxShape>(btVector3(100.0, 100.0, 5.0));
  box->setMargin(kCollisionMargin);
  btTransform pose;
  pose.setIdentity();
  pose.setOrigin(btVector3(0.0, 0.0, -5.0));
  bullet.ground_motion_state = std::make_unique<btDefaultMotionState>(pose);
  btRigidBody::btRigidBodyConstructionInfo info(0.0, bullet.ground_motion_state.get(), box.get());
  info.m_friction = friction_scale;
  info.m_restitution = 0.0;
  bullet.ground = std::make_unique<btRigidBody>(info);
  bullet.world.addRigidBody(bullet.ground.get(), btBroadphaseProxy::StaticFilter,
                            btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::StaticFilter);
  bullet.shapes.push_back(std::move(box));
}

/// The shape of every bump of `bumps`, centred on x = 0 at the floor's height: a box
/// reaching kBumpFooting into the floor (square edges), or the convex hull of the ramped
/// section swept along y.
std::unique_ptr<btCollisionShape> make_bump_shape(const FloorBumps& bumps) {
  if (!bumps.ramped()) {
    const double half_height = (bumps.height + kBumpFooting) / 2.0;
    auto box =
        std::make_unique<btBoxShape>(btVector3(bumps.width / 2.0, kBumpLength / 2.0, half_height));
    box->setMargin(kCollisionMargin);
    return box;
  }
  // A box keeps its margin inside its sides, a hull adds it around its points: the section
  // moves in by the margin so that the touched surface is the trapezoid's.
  auto hull = std::make_unique<btConvexHullShape>();
  for (const auto& [x, z] : bumps.ramped_section(kCollisionMargin)) {
    hull->addPoint(btVector3(x, kBumpLength / 2.0, z), false);
    hull->addPoint(btVector3(x, -kBumpLength / 2.0, z), false);
  }
  hull->setMargin(kCollisionMargin);
  hull->recalcLocalAabb();
  return hull;
}

/// The bumps of `bumps` as one static body with the ground's friction (Bullet's compound
/// keeps its children in a tree, so a tire meets only the nearest ones).
void add_bumps(BulletWorld& bullet, const FloorBumps& bumps, double friction_scale) {
  std::unique_ptr<btCollisionShape> bump = make_bump_shape(bumps);
  // The box is centred on its middle, the hull's points are around the floor's height.
  const double bump_z = bumps.ramped() ? 0.0 : bumps.height - (bumps.height + kBumpFooting) / 2.0;
  auto compound = std::make_unique<btCompoundShape>();
  btTransform pose;
  pose.setIdentity();
  for (const double x : bumps.centres()) {
    pose.setOrigin(btVector3(x, 0.0, bump_z));
    compound->addChildShape(pose, bump.get());
  }
  pose.setIdentity();
  bullet.bumps_motion_state = std::make_unique<btDefaultMotionState>(pose);
  btRigidBody::btRigidBodyConstructionInfo info(0.0, bullet.bumps_motion_state.get(),
                                                compound.get());
  info.m_friction = friction_scale;
  info.m_restitution = 0.0;
  bullet.bumps = std::make_unique<btRigidBody>(info);
  bullet.world.addRigidBody(bullet.bumps.get(), btBroadphaseProxy::StaticFilter,
                            btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::StaticFilter);
  bullet.shapes.push_back(std::move(bump));
  bullet.shapes.push_back(std::move(compound));
}

/// Contact parameters of a body: those of a soft (tire) shape if it has one, since the
/// shapes merged with a tire (hub, rotor) are smaller and never touch the floor.
ContactParameters body_contact(const RigidBody& body) {
  for (const auto& collision : body.collisions) {
    if (collision.contact.is_soft()) return collision.contact;
  }
  return body.collisions.empty() ? ContactParameters{} : body.collisions.front().contact;
}

/// Factor of the episode's variation on the mass and inertia of body `body` of `tree`.
double mass_scale(const RigidBodyTree& tree, int body, const PhysicsVariation& variation) {
  std::array<int, kNumServos> servo_bodies{};
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    servo_bodies[servo] = tree.servo_body(servo);
  }
  const auto parent_of = [&tree](int b) { return tree.bodies()[b].parent_body; };
  return variation.mass_scale[mass_scale_index(body, servo_bodies, parent_of)];
}

/// The root body's mass properties in this episode: scaled by its mass_scale, then with
/// the payload, if any, at its offset from the body's centre of mass.
MassProperties root_mass_properties(const RigidBodyTree& tree, const PhysicsVariation& variation) {
  const RigidBody& root = tree.bodies().front();
  const double scale = mass_scale(tree, 0, variation);
  MassProperties scaled{scale * root.mass, root.principal_frame, scale * root.principal_inertia};
  if (!variation.has_payload()) return scaled;
  return with_point_mass(scaled, variation.payload_mass,
                         root.principal_frame.translation() + variation.payload_offset);
}

/// Sets up the multibody's links: body b > 0 is link b - 1, link frames are the bodies'
/// principal frames (the root's is `root_com`, this episode's).
void setup_links(btMultiBody& multibody, const RigidBodyTree& tree, const RobotModel& model,
                 const PhysicsVariation& variation, const Eigen::Isometry3d& root_com) {
  const auto& bodies = tree.bodies();
  for (int b = 1; b < static_cast<int>(bodies.size()); ++b) {
    const RigidBody& body = bodies[b];
    const Eigen::Isometry3d& parent_com =
        body.parent_body == 0 ? root_com : bodies[body.parent_body].principal_frame;
    const Eigen::Isometry3d& com = body.principal_frame;
    const Eigen::Isometry3d joint_in_parent_com = parent_com.inverse() * body.joint_pose_in_parent;
    const Eigen::Matrix3d rotation_parent_com_to_com =
        (joint_in_parent_com.linear() * com.linear()).transpose();
    const btQuaternion rot_parent_to_this =
        to_bullet(Eigen::Quaterniond(rotation_parent_com_to_com));
    const btVector3 parent_com_to_pivot = to_bullet(joint_in_parent_com.translation());
    const btVector3 pivot_to_com =
        to_bullet(Eigen::Vector3d(com.linear().transpose() * com.translation()));
    const int parent_link = body.parent_body - 1;
    const Joint& joint = model.joints()[body.joint];
    const double scale = mass_scale(tree, b, variation);
    const double mass = scale * body.mass;
    const btVector3 inertia = to_bullet(Eigen::Vector3d(scale * body.principal_inertia));
    if (joint.type == Joint::Type::kFixed) {
      multibody.setupFixed(b - 1, mass, inertia, parent_link, rot_parent_to_this,
                           parent_com_to_pivot, pivot_to_com, true);
    } else {
      const Eigen::Vector3d axis_in_com = com.linear().transpose() * body.joint_axis;
      multibody.setupRevolute(b - 1, mass, inertia, parent_link, rot_parent_to_this,
                              to_bullet(axis_in_com), parent_com_to_pivot, pivot_to_com, true);
    }
  }
}

/// The collider of body `b`: one compound of its collision shapes, placed in its principal
/// frame `com`, with the body's contact parameters; the world keeps the shapes.
std::unique_ptr<btMultiBodyLinkCollider> make_collider(BulletWorld& bullet, const RigidBody& body,
                                                       int b, const Eigen::Isometry3d& com) {
  auto compound = std::make_unique<btCompoundShape>();
  for (const auto& collision : body.collisions) {
    auto child = make_shape(collision.shape);
    compound->addChildShape(
        to_bullet(Eigen::Isometry3d(com.inverse() * collision.shape.pose_in_link)), child.get());
    bullet.shapes.push_back(std::move(child));
  }
  auto collider = std::make_unique<btMultiBodyLinkCollider>(bullet.multibody.get(), b - 1);
  collider->setCollisionShape(compound.get());
  const ContactParameters contact = body_contact(body);
  collider->setFriction(contact.lateral_friction);
  collider->setRollingFriction(contact.rolling_friction);
  collider->setRestitution(0.0);
  if (contact.is_soft()) {
    collider->setContactStiffnessAndDamping(contact.stiffness, contact.damping);
  }
  bullet.shapes.push_back(std::move(compound));
  return collider;
}

/// A collider per body that has collision shapes; the tires' are remembered.
void add_colliders(BulletWorld& bullet, const RigidBodyTree& tree, const RobotModel& model) {
  btMultiBody& multibody = *bullet.multibody;
  const auto& bodies = tree.bodies();
  for (int b = 0; b < static_cast<int>(bodies.size()); ++b) {
    if (bodies[b].collisions.empty()) continue;
    const Eigen::Isometry3d& com = b == 0 ? bullet.base_com_in_base : bodies[b].principal_frame;
    std::unique_ptr<btMultiBodyLinkCollider> collider = make_collider(bullet, bodies[b], b, com);
    bullet.world.addCollisionObject(collider.get(), btBroadphaseProxy::DefaultFilter,
                                    btBroadphaseProxy::AllFilter);
    if (b == 0) {
      multibody.setBaseCollider(collider.get());
    } else {
      multibody.getLink(b - 1).m_collider = collider.get();
    }
    for (std::size_t wheel : {kLeftWheel, kRightWheel}) {
      if (tree.body_of_link(model.tire_link(wheel)) == b) {
        bullet.tires[wheel == kLeftWheel ? 0 : 1] = collider.get();
      }
    }
    bullet.colliders.push_back(std::move(collider));
  }
}

/// Hip and knee position limits as joint-limit constraints; no default joint motors.
void add_joint_limits(BulletWorld& bullet, const RobotModel& model) {
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    const JointLimits& limits = model.servo_limits(servo);
    if (!limits.has_position_limits()) continue;
    auto limit = std::make_unique<btMultiBodyJointLimitConstraint>(
        bullet.multibody.get(), bullet.servo_link[servo], limits.lower, limits.upper);
    bullet.world.addMultiBodyConstraint(limit.get());
    bullet.joint_limits.push_back(std::move(limit));
  }
}

void add_robot(BulletWorld& bullet, const RigidBodyTree& tree, const RobotModel& model,
               const PhysicsVariation& variation) {
  const int num_links = static_cast<int>(tree.bodies().size()) - 1;
  const MassProperties root = root_mass_properties(tree, variation);
  bullet.multibody =
      std::make_unique<btMultiBody>(num_links, root.mass, to_bullet(root.principal_inertia),
                                    /*fixedBase=*/false, /*canSleep=*/false);
  btMultiBody& multibody = *bullet.multibody;
  bullet.base_com_in_base = root.principal_frame;
  setup_links(multibody, tree, model, variation, root.principal_frame);
  multibody.finalizeMultiDof();
  multibody.setHasSelfCollision(false);
  multibody.setCanSleep(false);
  multibody.setLinearDamping(kLinkDamping);
  multibody.setAngularDamping(kLinkDamping);
  multibody.useGlobalVelocities(false);
  bullet.world.addMultiBody(&multibody);
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    bullet.servo_link[servo] = tree.servo_body(servo) - 1;
  }
  add_colliders(bullet, tree, model);
  add_joint_limits(bullet, model);
}

const BulletConfig& validated(const BulletConfig& config) {
  config.validate("BulletConfig");
  return config;
}

}  // namespace

BulletSimulation::BulletSimulation(std::shared_ptr<const RobotModel> model,
                                   const BulletConfig& config)
    : PhysicsSimulation(*model, validated(config)),
      model_(std::move(model)),
      config_(config),
      tree_(*model_, config.inertia_source, config.merge_fixed_links) {
  reset(ResetState{});
}

BulletSimulation::~BulletSimulation() = default;

const Observation& BulletSimulation::reset(const ResetState& state) {
  validate_reset_state(state);
  world_.reset();  // the old world goes first: the new one must not share its memory pools
  world_ = std::make_unique<BulletWorld>();
  configure_solver(world_->world, start_floor_slope(state));
  if (config_.floor) add_ground(*world_, variation().floor_friction_scale);
  if (config_.bumps.enabled() && variation().floor_bumps)
    add_bumps(*world_, config_.bumps, variation().floor_friction_scale);
  add_robot(*world_, tree_, *model_, variation());

  btMultiBody& multibody = *world_->multibody;
  const Eigen::Quaterniond orientation = state.orientation_base_in_world.normalized();
  Eigen::Isometry3d base_in_world = Eigen::Isometry3d::Identity();
  base_in_world.linear() = orientation.toRotationMatrix();
  base_in_world.translation() = state.position_base_in_world;
  const Eigen::Isometry3d com_in_world = base_in_world * world_->base_com_in_base;
  const Eigen::Vector3d angular_velocity_world =
      base_in_world.linear() * state.angular_velocity_base_in_base;
  const Eigen::Vector3d com_velocity =
      state.linear_velocity_base_to_world_in_world +
      angular_velocity_world.cross(com_in_world.translation() - base_in_world.translation());
  multibody.setBasePos(to_bullet(com_in_world.translation()));
  multibody.setWorldToBaseRot(to_bullet(Eigen::Quaterniond(com_in_world.linear()).inverse()));
  multibody.setBaseVel(to_bullet(com_velocity));
  multibody.setBaseOmega(to_bullet(angular_velocity_world));
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    multibody.setJointPos(world_->servo_link[servo], state.joint_configuration[servo]);
    multibody.setJointVel(world_->servo_link[servo], state.joint_velocities[servo]);
  }
  btAlignedObjectArray<btQuaternion> scratch_rotations;
  btAlignedObjectArray<btVector3> scratch_vectors;
  multibody.forwardKinematics(scratch_rotations, scratch_vectors);
  multibody.updateCollisionObjectWorldTransforms(scratch_rotations, scratch_vectors);

  return observe_reset();
}

void BulletSimulation::step_physics(const ServoAction& action, bool braked) {
  btMultiBody& multibody = *world_->multibody;
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    const int link = world_->servo_link[servo];
    multibody.addJointTorque(link,
                             joint_torque(servo, action[servo], braked, multibody.getJointPos(link),
                                          multibody.getJointVel(link)));
  }
  // The multibody's base is its centre of mass: the force acts there.
  if (!base_force().isZero(0.0)) multibody.addBaseForce(to_bullet(base_force()));
  world_->world.stepSimulation(config_.physics_timestep, 0, config_.physics_timestep);
}

void BulletSimulation::measure(MeasuredJoints& joints, MeasuredBase& base) const {
  const btMultiBody& multibody = *world_->multibody;
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    const int link = world_->servo_link[servo];
    joints.position[servo] = multibody.getJointPos(link);
    joints.velocity[servo] = multibody.getJointVel(link);
    joints.torque[servo] = applied_torques_[servo];
  }
  // Base link pose and velocity from the root body's COM frame.
  const Eigen::Quaterniond com_orientation = to_eigen(multibody.getWorldToBaseRot()).inverse();
  Eigen::Isometry3d com_in_world = Eigen::Isometry3d::Identity();
  com_in_world.linear() = com_orientation.toRotationMatrix();
  com_in_world.translation() = to_eigen(multibody.getBasePos());
  base.pose_in_world = com_in_world * world_->base_com_in_base.inverse();
  base.angular_velocity_in_world = to_eigen(multibody.getBaseOmega());
  base.linear_velocity_in_world =
      to_eigen(multibody.getBaseVel()) +
      base.angular_velocity_in_world.cross(base.pose_in_world.translation() -
                                           com_in_world.translation());
}

bool BulletSimulation::floor_contact(bool tires) const {
  if (!world_->ground) return false;
  const int num_manifolds = world_->dispatcher.getNumManifolds();
  for (int m = 0; m < num_manifolds; ++m) {
    const btPersistentManifold* manifold = world_->dispatcher.getManifoldByIndexInternal(m);
    const btCollisionObject* body0 = manifold->getBody0();
    const btCollisionObject* body1 = manifold->getBody1();
    const btCollisionObject* other =
        world_->is_ground(body0) ? body1 : (world_->is_ground(body1) ? body0 : nullptr);
    if (other == nullptr) continue;
    const bool tire = other == world_->tires[0] || other == world_->tires[1];
    if (tire != tires) continue;
    for (int p = 0; p < manifold->getNumContacts(); ++p) {
      if (manifold->getContactPoint(p).getDistance() < kTireContactDistance) return true;
    }
  }
  return false;
}

RobotMassDistribution BulletSimulation::mass_distribution() const {
  const btMultiBody& multibody = *world_->multibody;
  RobotMassDistribution distribution;
  distribution.base = {multibody.getBaseMass(), world_->base_com_in_base,
                       to_eigen(multibody.getBaseInertia())};
  // The base and the links are placed at their centres of mass (principal frames).
  distribution.total_mass = multibody.getBaseMass();
  Eigen::Vector3d weighted = multibody.getBaseMass() * to_eigen(multibody.getBasePos());
  for (int link = 0; link < multibody.getNumLinks(); ++link) {
    const double mass = multibody.getLink(link).m_mass;
    distribution.total_mass += mass;
    weighted += mass * to_eigen(multibody.localPosToWorld(link, btVector3(0.0, 0.0, 0.0)));
  }
  distribution.center_of_mass = weighted / distribution.total_mass;
  return distribution;
}

bool BulletSimulation::tire_touches_floor() const { return floor_contact(/*tires=*/true); }

bool BulletSimulation::non_tire_touches_floor() const { return floor_contact(/*tires=*/false); }

}  // namespace upkie_rl
