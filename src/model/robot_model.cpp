#include "model/robot_model.hpp"

#include <console_bridge/console.h>
#include <tinyxml.h>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <cstdlib>
#include <functional>
#include <map>
#include <mutex>
#include <numeric>
#include <sstream>

#include "base/input_file.hpp"
#include "model/robot_description_limit.hpp"

namespace upkie_rl {
namespace {

/// Collects urdfdom's error messages (it reports through console_bridge) so that our
/// exception can say which element was at fault.
class CapturingOutputHandler : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char* /*file*/,
           int /*line*/) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR) {
      messages_.push_back(text);
    }
  }
  std::string joined() const {
    std::string result;
    for (const auto& message : messages_) {
      result += (result.empty() ? "" : "; ") + message;
    }
    return result;
  }

 private:
  std::vector<std::string> messages_;
};

Eigen::Isometry3d to_isometry(const urdf::Pose& pose) {
  Eigen::Isometry3d result = Eigen::Isometry3d::Identity();
  result.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  result.linear() =
      Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z)
          .normalized()
          .toRotationMatrix();
  return result;
}

std::string read_file(const std::filesystem::path& path) {
  return read_input_file<ModelError>(path, "robot description", kMaxRobotDescriptionBytes);
}

double parse_value_attribute(const TiXmlElement& element, const std::filesystem::path& path,
                             const std::string& link_name) {
  double value = 0.0;
  if (element.QueryDoubleAttribute("value", &value) != TIXML_SUCCESS || !std::isfinite(value)) {
    throw ModelError(path.string() + ": link '" + link_name + "': <contact><" + element.ValueStr() +
                     "> needs a finite numeric value attribute");
  }
  return value;
}

/// Reads the Bullet `<contact>` extension of each link, which urdfdom ignores.
std::map<std::string, ContactParameters> parse_contact_parameters(
    const std::string& xml, const std::filesystem::path& path) {
  TiXmlDocument document;
  document.Parse(xml.c_str());
  if (document.Error()) {
    std::ostringstream message;
    message << path.string() << ":" << document.ErrorRow() << ":" << document.ErrorCol()
            << ": malformed XML: " << document.ErrorDesc();
    throw ModelError(message.str());
  }
  std::map<std::string, ContactParameters> result;
  const TiXmlElement* robot = document.FirstChildElement("robot");
  if (robot == nullptr) {
    throw ModelError(path.string() + ": no <robot> element");
  }
  for (const TiXmlElement* link = robot->FirstChildElement("link"); link != nullptr;
       link = link->NextSiblingElement("link")) {
    const TiXmlElement* contact = link->FirstChildElement("contact");
    const char* name = link->Attribute("name");
    if (contact == nullptr || name == nullptr) {
      continue;
    }
    ContactParameters parameters;
    for (const TiXmlElement* item = contact->FirstChildElement(); item != nullptr;
         item = item->NextSiblingElement()) {
      const std::string tag = item->ValueStr();
      if (tag == "lateral_friction") {
        parameters.lateral_friction = parse_value_attribute(*item, path, name);
      } else if (tag == "rolling_friction") {
        parameters.rolling_friction = parse_value_attribute(*item, path, name);
      } else if (tag == "stiffness") {
        parameters.stiffness = parse_value_attribute(*item, path, name);
      } else if (tag == "damping") {
        parameters.damping = parse_value_attribute(*item, path, name);
      }
    }
    result[name] = parameters;
  }
  return result;
}

urdf::ModelInterfaceSharedPtr parse_with_urdfdom(const std::string& xml,
                                                 const std::filesystem::path& path) {
  // console_bridge's handler is process-wide: serialise parses that swap it.
  static std::mutex handler_mutex;
  std::lock_guard<std::mutex> lock(handler_mutex);
  CapturingOutputHandler handler;
  console_bridge::useOutputHandler(&handler);
  urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(xml);
  console_bridge::restorePreviousOutputHandler();
  if (!model) {
    throw ModelError(path.string() + ": invalid robot description: " + handler.joined());
  }
  return model;
}

CollisionShape to_collision_shape(const urdf::Collision& collision, const std::string& link_name,
                                  const std::filesystem::path& path) {
  CollisionShape shape;
  shape.pose_in_link = to_isometry(collision.origin);
  if (!collision.geometry) {
    throw ModelError(path.string() + ": link '" + link_name + "': <collision> has no geometry");
  }
  switch (collision.geometry->type) {
    case urdf::Geometry::BOX: {
      const auto& box = static_cast<const urdf::Box&>(*collision.geometry);
      shape.kind = CollisionShape::Kind::kBox;
      shape.box_size = Eigen::Vector3d(box.dim.x, box.dim.y, box.dim.z);
      break;
    }
    case urdf::Geometry::CYLINDER: {
      const auto& cylinder = static_cast<const urdf::Cylinder&>(*collision.geometry);
      shape.kind = CollisionShape::Kind::kCylinder;
      shape.radius = cylinder.radius;
      shape.length = cylinder.length;
      break;
    }
    default:
      throw ModelError(path.string() + ": link '" + link_name +
                       "': unsupported collision geometry (only box and cylinder are)");
  }
  return shape;
}

Joint to_joint(const urdf::Joint& urdf_joint, const std::filesystem::path& path) {
  Joint joint;
  joint.name = urdf_joint.name;
  joint.origin = to_isometry(urdf_joint.parent_to_joint_origin_transform);
  joint.axis = Eigen::Vector3d(urdf_joint.axis.x, urdf_joint.axis.y, urdf_joint.axis.z);
  switch (urdf_joint.type) {
    case urdf::Joint::FIXED:
      joint.type = Joint::Type::kFixed;
      return joint;
    case urdf::Joint::REVOLUTE:
      joint.type = Joint::Type::kRevolute;
      break;
    case urdf::Joint::CONTINUOUS:
      joint.type = Joint::Type::kContinuous;
      break;
    default:
      throw ModelError(path.string() + ": joint '" + joint.name +
                       "': unsupported type (only fixed, revolute and continuous are)");
  }
  if (joint.axis.norm() < 1e-9) {
    throw ModelError(path.string() + ": joint '" + joint.name + "': zero <axis>");
  }
  joint.axis.normalize();
  if (!urdf_joint.limits) {
    throw ModelError(path.string() + ": joint '" + joint.name + "': missing <limit>");
  }
  joint.limits.effort = urdf_joint.limits->effort;
  joint.limits.velocity = urdf_joint.limits->velocity;
  if (joint.type == Joint::Type::kRevolute) {
    joint.limits.lower = urdf_joint.limits->lower;
    joint.limits.upper = urdf_joint.limits->upper;
    if (!(joint.limits.lower < joint.limits.upper)) {
      throw ModelError(path.string() + ": joint '" + joint.name +
                       "': <limit> lower must be below upper");
    }
  }
  if (!(joint.limits.effort > 0.0) || !(joint.limits.velocity > 0.0)) {
    throw ModelError(path.string() + ": joint '" + joint.name +
                     "': <limit> effort and velocity must be positive");
  }
  return joint;
}

Link to_link(const urdf::Link& urdf_link, int parent_joint,
             const std::map<std::string, ContactParameters>& contacts,
             const std::filesystem::path& path) {
  Link link;
  link.name = urdf_link.name;
  link.parent_joint = parent_joint;
  if (urdf_link.inertial) {
    const auto& inertial = *urdf_link.inertial;
    link.mass = inertial.mass;
    link.inertial_pose = to_isometry(inertial.origin);
    link.urdf_inertia << inertial.ixx, inertial.ixy, inertial.ixz, inertial.ixy, inertial.iyy,
        inertial.iyz, inertial.ixz, inertial.iyz, inertial.izz;
    if (!(link.mass >= 0.0) || !link.urdf_inertia.allFinite()) {
      throw ModelError(path.string() + ": link '" + link.name +
                       "': <inertial> mass must be non-negative and values finite");
    }
  }
  for (const auto& collision : urdf_link.collision_array) {
    link.collisions.push_back(to_collision_shape(*collision, link.name, path));
  }
  if (auto found = contacts.find(link.name); found != contacts.end()) {
    link.contact = found->second;
  }
  return link;
}

/// The links and joints of the tree under `urdf_link`, appended depth-first, children in
/// document order: a deterministic numbering.
void add_link_tree(const urdf::ModelInterface& urdf_model,
                   const urdf::LinkConstSharedPtr& urdf_link, int parent_joint,
                   const std::map<std::string, ContactParameters>& contacts,
                   const std::filesystem::path& path, std::vector<Link>& links,
                   std::vector<Joint>& joints) {
  const int link_index = static_cast<int>(links.size());
  links.push_back(to_link(*urdf_link, parent_joint, contacts, path));
  if (parent_joint >= 0) joints[parent_joint].child_link = link_index;
  for (const auto& child_joint : urdf_link->child_joints) {
    Joint joint = to_joint(*child_joint, path);
    joint.parent_link = link_index;
    const int joint_index = static_cast<int>(joints.size());
    joints.push_back(std::move(joint));
    add_link_tree(urdf_model, urdf_model.getLink(child_joint->child_link_name), joint_index,
                  contacts, path, links, joints);
  }
}

/// The joints of the six servos, in the standard order.
std::array<int, kNumServos> find_servo_joints(const std::vector<Joint>& joints,
                                              const std::filesystem::path& path) {
  std::array<int, kNumServos> servo_joints{};
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    const std::string name(kServoNames[servo]);
    auto found = std::find_if(joints.begin(), joints.end(),
                              [&](const Joint& joint) { return joint.name == name; });
    if (found == joints.end() || found->type == Joint::Type::kFixed) {
      throw ModelError(path.string() + ": joint '" + name +
                       "' is missing or not actuated; Upkie needs left_hip, left_knee, "
                       "left_wheel, right_hip, right_knee, right_wheel");
    }
    servo_joints[servo] = static_cast<int>(found - joints.begin());
  }
  return servo_joints;
}

/// The tire of a wheel: the largest cylinder rigidly attached to its joint.
struct Tire {
  double radius = 0.0;
  int link = -1;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< In the root frame, at zero.
};

Tire find_tire(const std::vector<Link>& links, const std::vector<Joint>& joints,
               const std::vector<Eigen::Isometry3d>& poses, const Joint& wheel_joint,
               const std::filesystem::path& path) {
  Tire tire;
  std::function<void(int)> visit = [&](int link_index) {
    const Link& link = links[link_index];
    for (const auto& shape : link.collisions) {
      if (shape.kind == CollisionShape::Kind::kCylinder && shape.radius > tire.radius) {
        tire.radius = shape.radius;
        tire.link = link_index;
        tire.centre = (poses[link_index] * shape.pose_in_link).translation();
      }
    }
    for (const Joint& joint : joints) {
      if (joint.parent_link == link_index && joint.type == Joint::Type::kFixed) {
        visit(joint.child_link);
      }
    }
  };
  visit(wheel_joint.child_link);
  if (tire.radius <= 0.0) {
    throw ModelError(path.string() + ": no tire <cylinder> collision rigidly attached to joint '" +
                     wheel_joint.name + "'");
  }
  return tire;
}

}  // namespace

RobotModel RobotModel::from_urdf_file(const std::filesystem::path& path) {
  const std::string xml = read_file(path);
  const auto contacts = parse_contact_parameters(xml, path);
  const urdf::ModelInterfaceSharedPtr urdf_model = parse_with_urdfdom(xml, path);

  RobotModel model;
  model.path_ = path;
  add_link_tree(*urdf_model, urdf_model->getRoot(), -1, contacts, path, model.links_,
                model.joints_);
  model.root_link_ = 0;
  model.servo_joints_ = find_servo_joints(model.joints_, path);

  const auto poses = model.link_poses_at_zero();
  // Wheel radius and track from the tires.
  const auto wheel_joint = [&model](std::size_t servo) -> const Joint& {
    return model.joints_[model.servo_joints_[servo]];
  };
  const Tire left = find_tire(model.links_, model.joints_, poses, wheel_joint(kLeftWheel), path);
  const Tire right = find_tire(model.links_, model.joints_, poses, wheel_joint(kRightWheel), path);
  model.tire_links_ = {left.link, right.link};
  model.wheel_radius_ = left.radius;
  model.track_ = (left.centre - right.centre).norm();

  // A positive rotation about an axis along +y (root frame) rolls a wheel forward.
  const Joint& left_wheel = wheel_joint(kLeftWheel);
  const Eigen::Vector3d left_axis = poses[left_wheel.child_link].linear() * left_wheel.axis;
  model.left_wheeled_ = left_axis.y() > 0.0;

  const auto imu = model.find_link("imu");
  if (!imu) {
    throw ModelError(path.string() + ": no link named 'imu'");
  }
  model.rotation_base_to_imu_ = poses[*imu].linear();
  model.imu_position_in_base_ = poses[*imu].translation();
  return model;
}

std::filesystem::path RobotModel::default_urdf_path() {
  if (const char* override_path = std::getenv("UPKIE_RL_MODEL")) {
    return override_path;
  }
  return UPKIE_RL_MODEL_PATH;
}

std::shared_ptr<const RobotModel> RobotModel::default_model() {
  static const std::shared_ptr<const RobotModel> kModel =
      std::make_shared<const RobotModel>(from_urdf_file(default_urdf_path()));
  return kModel;
}

std::optional<int> RobotModel::find_link(const std::string& name) const {
  for (std::size_t i = 0; i < links_.size(); ++i) {
    if (links_[i].name == name) {
      return static_cast<int>(i);
    }
  }
  return std::nullopt;
}

double RobotModel::total_mass() const {
  return std::accumulate(links_.begin(), links_.end(), 0.0,
                         [](double sum, const Link& link) { return sum + link.mass; });
}

std::vector<Eigen::Isometry3d> RobotModel::link_poses_at_zero() const {
  // Links are numbered depth-first, so a parent always precedes its children.
  std::vector<Eigen::Isometry3d> poses(links_.size(), Eigen::Isometry3d::Identity());
  for (std::size_t i = 0; i < links_.size(); ++i) {
    const int joint = links_[i].parent_joint;
    if (joint >= 0) {
      poses[i] = poses[joints_[joint].parent_link] * joints_[joint].origin;
    }
  }
  return poses;
}

}  // namespace upkie_rl
