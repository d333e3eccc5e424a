#include "sim/mujoco_model.hpp"

#include <mujoco/mujoco.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim/tire_contact.hpp"

namespace upkie_rl {

void MujocoModelDeleter::operator()(mjModel* model) const { mj_deleteModel(model); }
void MujocoDataDeleter::operator()(mjData* data) const { mj_deleteData(data); }

namespace {

constexpr const char* kFloorName = "floor";
/// The reference ground's lateral friction; the bumps on it have the same.
constexpr double kFloorFriction = 1.0;

/// Deletes an mjSpec on every path out of build_mujoco_model.
struct SpecDeleter {
  void operator()(mjSpec* spec) const { mj_deleteSpec(spec); }
};

void set_pose(const Eigen::Isometry3d& pose, double pos[3], double quat[4]) {
  const Eigen::Quaterniond rotation(pose.linear());
  for (int i = 0; i < 3; ++i) pos[i] = pose.translation()[i];
  quat[0] = rotation.w();
  quat[1] = rotation.x();
  quat[2] = rotation.y();
  quat[3] = rotation.z();
}

/// Tire contact as a spring-damper: MuJoCo's direct solref (-k, -b) is per unit of the
/// contact's effective mass, so the URDF's stiffness [N/m] and damping [N.s/m] are divided
/// by the mass each tire carries standing (half the robot's).
void set_soft_contact(mjsGeom& geom, const ContactParameters& contact, double carried_mass) {
  geom.solref[0] = -contact.stiffness / carried_mass;
  geom.solref[1] = -contact.damping / carried_mass;
}

void add_collision_geoms(mjsBody& body, const RigidBody& rigid_body, const RobotModel& robot,
                         const MujocoConfig& config, double tire_carried_mass) {
  for (const BodyCollision& collision : rigid_body.collisions) {
    mjsGeom* geom = mjs_addGeom(&body, nullptr);
    const CollisionShape& shape = collision.shape;
    set_pose(shape.pose_in_link, geom->pos, geom->quat);
    if (shape.kind == CollisionShape::Kind::kBox) {
      geom->type = mjGEOM_BOX;
      for (int i = 0; i < 3; ++i) geom->size[i] = shape.box_size[i] / 2.0;
    } else {
      geom->type = mjGEOM_CYLINDER;
      geom->size[0] = shape.radius;
      geom->size[1] = shape.length / 2.0;
    }
    // Robot geoms touch the floor, never each other (as in Bullet, without self-collision).
    geom->contype = 1;
    geom->conaffinity = 0;
    geom->condim = 3;
    geom->friction[0] = collision.contact.lateral_friction;
    geom->friction[1] = 0.0;
    geom->friction[2] = 0.0;
    geom->rgba[0] = 0.92f;  // drawn orange, tires black, on a light grey floor
    geom->rgba[1] = 0.55f;
    geom->rgba[2] = 0.18f;
    geom->rgba[3] = 1.0f;
    const bool tire = collision.link == robot.tire_link(kLeftWheel) ||
                      collision.link == robot.tire_link(kRightWheel);
    if (tire) {
      geom->condim = config.tire_condim;
      geom->friction[2] = collision.contact.rolling_friction;  // [m], as Bullet's
      geom->priority = 1;  // its friction, not the floor's, applies
      // Contacts within 1 mm are detected (floor_contact, as Bullet's threshold) but only
      // penetrating ones push.
      geom->margin = kTireContactDistance;
      geom->gap = kTireContactDistance;
      if (collision.contact.is_soft())
        set_soft_contact(*geom, collision.contact, tire_carried_mass);
      geom->rgba[0] = geom->rgba[1] = geom->rgba[2] = 0.12f;
      const std::string name =
          collision.link == robot.tire_link(kLeftWheel) ? "left_tire" : "right_tire";
      mjs_setName(geom->element, name.c_str());
    }
  }
}

void add_scene(mjSpec& spec, mjsBody& world) {
  mjsTexture* texture = mjs_addTexture(&spec);
  mjs_setName(texture->element, "grid");
  texture->type = mjTEXTURE_2D;
  texture->builtin = mjBUILTIN_CHECKER;
  texture->width = 512;
  texture->height = 512;
  const double light[3] = {0.93, 0.94, 0.95};
  const double dark[3] = {0.80, 0.82, 0.85};
  for (int i = 0; i < 3; ++i) {
    texture->rgb1[i] = light[i];
    texture->rgb2[i] = dark[i];
  }
  mjsMaterial* material = mjs_addMaterial(&spec, nullptr);
  mjs_setName(material->element, "grid");
  mjs_setInStringVec(material->textures, mjTEXROLE_RGB, "grid");
  material->texrepeat[0] = 4.0f;
  material->texrepeat[1] = 4.0f;
  material->texuniform = 1;
  material->reflectance = 0.0f;  // a reflection draws the scene twice: half the frame rate

  mjsLight* sun = mjs_addLight(&world, nullptr);
  sun->pos[2] = 3.0;
  sun->dir[0] = 0.3;
  sun->dir[1] = 0.3;
  sun->dir[2] = -1.0;
  sun->type = mjLIGHT_DIRECTIONAL;
  sun->castshadow = 0;  // shadows double the time of a software-rendered frame
  sun->diffuse[0] = sun->diffuse[1] = sun->diffuse[2] = 0.7f;
  spec.visual.headlight.ambient[0] = spec.visual.headlight.ambient[1] =
      spec.visual.headlight.ambient[2] = 0.35f;
  spec.visual.headlight.diffuse[0] = spec.visual.headlight.diffuse[1] =
      spec.visual.headlight.diffuse[2] = 0.4f;
  spec.visual.global.offwidth = 1920;
  spec.visual.global.offheight = 1080;
  spec.visual.quality.offsamples = 0;  // multisampling triples it
}

void add_floor(mjsBody& world) {
  mjsGeom* floor = mjs_addGeom(&world, nullptr);
  mjs_setName(floor->element, kFloorName);
  floor->type = mjGEOM_PLANE;
  floor->size[0] = 100.0;  // as Bullet's 200 m x 200 m ground box
  floor->size[1] = 100.0;
  floor->size[2] = 0.05;  // grid spacing of the drawn plane [m]
  floor->group = 2;       // drawn apart from the robot's geoms (group 0)
  floor->contype = 0;
  floor->conaffinity = 1;
  floor->condim = 3;
  floor->friction[0] = kFloorFriction;
  floor->friction[1] = 0.0;
  floor->friction[2] = 0.0;
  mjs_setString(floor->material, "grid");
}

std::string bump_name(std::size_t bump) { return "bump_" + std::to_string(bump); }
constexpr const char* kBumpMeshName = "bump";

/// The mesh every ramped bump's geom shows: the section of `bumps` swept along y, centred on
/// x = 0 with the floor at z = 0 (MuJoCo collides with its convex hull, which it is).
void add_bump_mesh(mjSpec& spec, const FloorBumps& bumps) {
  mjsMesh* mesh = mjs_addMesh(&spec, nullptr);
  mjs_setName(mesh->element, kBumpMeshName);
  std::vector<float> vertices;
  for (const auto& [x, z] : bumps.ramped_section()) {
    for (const double y : {kBumpLength / 2.0, -kBumpLength / 2.0}) {
      vertices.insert(vertices.end(),
                      {static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)});
    }
  }
  mjs_setFloat(mesh->uservert, vertices.data(), static_cast<int>(vertices.size()));
}

/// Makes `geom` the bump of `bumps` centred on x = `centre`: a box reaching kBumpFooting into
/// the floor (square edges), or the ramped mesh.
void set_bump_shape(mjsGeom& geom, const FloorBumps& bumps, double centre) {
  geom.pos[0] = centre;
  if (bumps.ramped()) {
    geom.type = mjGEOM_MESH;
    mjs_setString(geom.meshname, kBumpMeshName);
    return;
  }
  geom.type = mjGEOM_BOX;
  geom.size[0] = bumps.width / 2.0;
  geom.size[1] = kBumpLength / 2.0;
  geom.size[2] = (bumps.height + kBumpFooting) / 2.0;
  geom.pos[2] = (bumps.height - kBumpFooting) / 2.0;
}

/// A static geom per bump of `bumps`, touched by the robot as the floor is (the tires'
/// contact priority makes their friction and softness the contact's, as on the floor).
void add_bumps(mjSpec& spec, mjsBody& world, const FloorBumps& bumps) {
  const std::vector<double> centres = bumps.centres();
  if (bumps.ramped() && !centres.empty()) add_bump_mesh(spec, bumps);
  for (std::size_t bump = 0; bump < centres.size(); ++bump) {
    mjsGeom* geom = mjs_addGeom(&world, nullptr);
    mjs_setName(geom->element, bump_name(bump).c_str());
    set_bump_shape(*geom, bumps, centres[bump]);
    geom->group = 2;  // drawn with the floor
    geom->contype = 0;
    geom->conaffinity = 1;
    geom->condim = 3;
    geom->friction[0] = kFloorFriction;
    geom->friction[1] = 0.0;
    geom->friction[2] = 0.0;
    geom->rgba[0] = geom->rgba[1] = geom->rgba[2] = 0.45f;  // darker than the floor's grid
    geom->rgba[3] = 1.0f;
  }
}

int checked_id(const mjModel* model, mjtObj type, const std::string& name) {
  const int id = mj_name2id(model, type, name.c_str());
  if (id < 0) throw ModelError("MuJoCo model: no element named \"" + name + "\"");
  return id;
}

void silence(const char* message) { spdlog::warn("MuJoCo: {}", message); }

/// A spec whose compiler takes the tree's values as they are, and the config's options.
std::unique_ptr<mjSpec, SpecDeleter> make_spec(const MujocoConfig& config) {
  std::unique_ptr<mjSpec, SpecDeleter> spec(mj_makeSpec());
  mjs_setString(spec->modelname, "upkie");
  spec->compiler.inertiafromgeom = mjINERTIAFROMGEOM_FALSE;  // the tree's inertias, exactly
  spec->compiler.alignfree = mjALIGNFREE_FALSE;              // free joint at the base link frame
  spec->compiler.degree = 0;  // joint ranges in radians, as in the URDF
  spec->compiler.autolimits = 1;
  spec->compiler.boundmass = 0.0;
  spec->compiler.boundinertia = 0.0;
  mjOption& option = spec->option;
  option.timestep = config.physics_timestep;
  option.gravity[0] = 0.0;
  option.gravity[1] = 0.0;
  option.gravity[2] = -config.gravity;
  option.iterations = config.solver_iterations;
  option.integrator = mjINT_EULER;
  // Divergence is reported as SimulationDivergedError, not silently reset.
  option.disableflags |= mjDSBL_AUTORESET;
  return spec;
}

/// The hinge of `joint` in `body`, with its position limits.
void add_hinge(mjsBody& body, const Joint& joint, const Eigen::Vector3d& axis,
               const MujocoConfig& config) {
  mjsJoint* hinge = mjs_addJoint(&body, nullptr);
  mjs_setName(hinge->element, joint.name.c_str());
  hinge->type = mjJNT_HINGE;
  for (int i = 0; i < 3; ++i) hinge->axis[i] = axis[i];
  if (!joint.limits.has_position_limits()) {
    hinge->limited = mjLIMITED_FALSE;
    return;
  }
  hinge->limited = mjLIMITED_TRUE;
  hinge->range[0] = joint.limits.lower;
  hinge->range[1] = joint.limits.upper;
  // Stiff limits: MuJoCo's default (a 20 ms time constant) lets a hip swung at full
  // effort pass its limit by 0.5 rad; the stiffest stable one is two physics steps.
  hinge->solref_limit[0] = 2.0 * config.physics_timestep;
  hinge->solref_limit[1] = 1.0;
  hinge->solimp_limit[0] = 0.99;
  hinge->solimp_limit[1] = 0.999;
}

/// A body of `spec` per body of `tree` (the root on a free joint), with its collision geoms.
void add_bodies(mjsBody& world, const RigidBodyTree& tree, const RobotModel& robot,
                const MujocoConfig& config) {
  const double tire_carried_mass = robot.total_mass() / 2.0;
  std::vector<mjsBody*> bodies;
  for (const RigidBody& rigid_body : tree.bodies()) {
    mjsBody* parent = rigid_body.parent_body < 0 ? &world : bodies[rigid_body.parent_body];
    mjsBody* body = mjs_addBody(parent, nullptr);
    bodies.push_back(body);
    mjs_setName(body->element, rigid_body.name.c_str());
    set_pose(rigid_body.joint_pose_in_parent, body->pos, body->quat);
    body->mass = rigid_body.mass;
    set_pose(rigid_body.principal_frame, body->ipos, body->iquat);
    for (int i = 0; i < 3; ++i) body->inertia[i] = rigid_body.principal_inertia[i];
    body->explicitinertial = 1;
    if (rigid_body.parent_body < 0) {
      mjsJoint* free_joint = mjs_addFreeJoint(body);
      mjs_setName(free_joint->element, "base_free");
    } else {
      add_hinge(*body, robot.joints()[rigid_body.joint], rigid_body.joint_axis, config);
    }
    add_collision_geoms(*body, rigid_body, robot, config, tire_carried_mass);
  }
}

/// Where the robot's bodies, joints and tires are in the compiled `model`.
MujocoRobotIndex index_robot(const mjModel* model, const RigidBodyTree& tree,
                             const RobotModel& robot, const MujocoConfig& config) {
  MujocoRobotIndex index;
  index.root_body = checked_id(model, mjOBJ_BODY, tree.bodies().front().name);
  const int free_joint = checked_id(model, mjOBJ_JOINT, "base_free");
  index.root_qpos = model->jnt_qposadr[free_joint];
  index.root_dof = model->jnt_dofadr[free_joint];
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    const std::string& name = robot.joints()[robot.servo_joint(servo)].name;
    const int joint = checked_id(model, mjOBJ_JOINT, name);
    index.servo_qpos[servo] = model->jnt_qposadr[joint];
    index.servo_dof[servo] = model->jnt_dofadr[joint];
    index.servo_body[servo] = model->jnt_bodyid[joint];
  }
  index.tire_geoms[0] = checked_id(model, mjOBJ_GEOM, "left_tire");
  index.tire_geoms[1] = checked_id(model, mjOBJ_GEOM, "right_tire");
  if (config.floor) index.floor_geom = checked_id(model, mjOBJ_GEOM, kFloorName);
  const std::size_t num_bumps = config.bumps.centres().size();
  if (num_bumps > 0) {
    index.first_bump_geom = checked_id(model, mjOBJ_GEOM, bump_name(0));
    index.num_bump_geoms = static_cast<int>(num_bumps);
    // Added one after the other to the world body, so numbered in a row: checked, since
    // is_ground relies on it.
    if (checked_id(model, mjOBJ_GEOM, bump_name(num_bumps - 1)) !=
        index.first_bump_geom + index.num_bump_geoms - 1) {
      throw ModelError("MuJoCo model: the bumps' geoms are not numbered in a row");
    }
  }
  return index;
}

}  // namespace

void route_mujoco_messages() {
  static std::once_flag once;
  std::call_once(once, [] { mju_user_warning = silence; });
}

std::shared_ptr<const MujocoModel> build_mujoco_model(const RobotModel& robot,
                                                      const MujocoConfig& config) {
  config.validate();  // the bumps' spacing, say, bounds the number of geoms
  route_mujoco_messages();
  const RigidBodyTree tree(robot, config.inertia_source, /*merge_fixed_links=*/true);
  const std::unique_ptr<mjSpec, SpecDeleter> spec = make_spec(config);
  mjsBody* world = mjs_findBody(spec.get(), "world");
  add_scene(*spec, *world);
  if (config.floor) {
    add_floor(*world);
    add_bumps(*spec, *world, config.bumps);
  }
  add_bodies(*world, tree, robot, config);

  MujocoModelPtr model(mj_compile(spec.get(), nullptr));
  if (!model) {
    throw ModelError(std::string("MuJoCo could not compile the model of ") + robot.path().string() +
                     ": " + mjs_getError(spec.get()));
  }
  auto result = std::make_shared<MujocoModel>();
  result->index = index_robot(model.get(), tree, robot, config);
  result->model = std::move(model);
  return result;
}

}  // namespace upkie_rl
