#include "model/rigid_body_tree.hpp"

#include <Eigen/Eigenvalues>
#include <limits>

namespace upkie_rl {
namespace {

/// Side of the cube whose inertia Bullet gives a link without collision shapes [m].
constexpr double kNoShapeCubeSide = 0.002;

/// Number of sides of the convex hull Bullet builds for a URDF cylinder.
constexpr int kCylinderHullSides = 32;

Eigen::Matrix3d box_inertia(double mass, const Eigen::Vector3d& sides) {
  const Eigen::Vector3d squared = sides.cwiseProduct(sides);
  return (mass / 12.0 *
          Eigen::Vector3d(squared.y() + squared.z(), squared.x() + squared.z(),
                          squared.x() + squared.y()))
      .asDiagonal();
}

/// Extends `low`/`high` with the shape's vertices expressed in `frame`.
void extend_bounding_box(const CollisionShape& shape, const Eigen::Isometry3d& frame,
                         Eigen::Vector3d* low, Eigen::Vector3d* high) {
  const Eigen::Isometry3d shape_in_frame = frame.inverse() * shape.pose_in_link;
  auto add = [&](const Eigen::Vector3d& vertex) {
    const Eigen::Vector3d point = shape_in_frame * vertex;
    *low = low->cwiseMin(point);
    *high = high->cwiseMax(point);
  };
  if (shape.kind == CollisionShape::Kind::kBox) {
    const Eigen::Vector3d half = shape.box_size / 2.0;
    for (int corner = 0; corner < 8; ++corner) {
      add(Eigen::Vector3d((corner & 1) ? half.x() : -half.x(), (corner & 2) ? half.y() : -half.y(),
                          (corner & 4) ? half.z() : -half.z()));
    }
  } else {
    // The hull Bullet simulates: 32 vertices on each cap circle, inflated by 3 margins per
    // side in its bounding box (what PyBullet's inertia computation does).
    const double inflate = 3.0 * kCollisionMargin;
    for (int i = 0; i < kCylinderHullSides; ++i) {
      const double angle = 2.0 * M_PI * i / kCylinderHullSides;
      const double r = shape.radius + inflate;
      for (double z : {-shape.length / 2.0 - inflate, shape.length / 2.0 + inflate}) {
        add(Eigen::Vector3d(r * std::sin(angle), r * std::cos(angle), z));
      }
    }
  }
}

}  // namespace

Eigen::Matrix3d link_inertia(const Link& link, InertiaSource source) {
  if (source == InertiaSource::kUrdf) {
    return link.urdf_inertia;
  }
  if (link.collisions.empty()) {
    return box_inertia(link.mass, Eigen::Vector3d::Constant(kNoShapeCubeSide));
  }
  Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d high = -low;
  for (const auto& shape : link.collisions) {
    extend_bounding_box(shape, link.inertial_pose, &low, &high);
  }
  return box_inertia(link.mass, high - low);
}

namespace {

/// Sets the mass, collisions, centre of mass and principal inertia of `body` from those of
/// its links (parallel-axis theorem); `link_in_body` places each link in its body.
void set_composite_inertia(RigidBody& body, const std::vector<Link>& links,
                           const std::vector<Eigen::Isometry3d>& link_in_body,
                           InertiaSource source) {
  Eigen::Vector3d weighted_com = Eigen::Vector3d::Zero();
  for (int link : body.links) {
    const Eigen::Isometry3d inertial_in_body = link_in_body[link] * links[link].inertial_pose;
    body.mass += links[link].mass;
    weighted_com += links[link].mass * inertial_in_body.translation();
    for (const auto& shape : links[link].collisions) {
      BodyCollision collision{shape, links[link].contact, link};
      collision.shape.pose_in_link = link_in_body[link] * shape.pose_in_link;
      body.collisions.push_back(collision);
    }
  }
  const Eigen::Vector3d com =
      body.mass > 0.0 ? Eigen::Vector3d(weighted_com / body.mass) : Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  for (int link : body.links) {
    const Eigen::Isometry3d inertial_in_body = link_in_body[link] * links[link].inertial_pose;
    const Eigen::Matrix3d rotation = inertial_in_body.linear();
    const Eigen::Vector3d offset = inertial_in_body.translation() - com;
    inertia += rotation * link_inertia(links[link], source) * rotation.transpose() +
               links[link].mass * (offset.squaredNorm() * Eigen::Matrix3d::Identity() -
                                   offset * offset.transpose());
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(inertia);
  Eigen::Matrix3d axes = solver.eigenvectors();
  if (axes.determinant() < 0.0) {
    axes.col(2) = -axes.col(2);
  }
  // Keep the link frame when it is already principal (single links), for readability.
  if ((inertia - Eigen::Matrix3d(inertia.diagonal().asDiagonal())).norm() <=
      1e-12 * std::max(1e-12, inertia.norm())) {
    axes.setIdentity();
    body.principal_inertia = inertia.diagonal();
  } else {
    body.principal_inertia = solver.eigenvalues();
  }
  body.principal_frame.linear() = axes;
  body.principal_frame.translation() = com;
}

}  // namespace

RigidBodyTree::RigidBodyTree(const RobotModel& model, InertiaSource source,
                             bool merge_fixed_links) {
  const auto& links = model.links();
  const auto& joints = model.joints();
  body_of_link_.assign(links.size(), -1);
  link_in_body_.assign(links.size(), Eigen::Isometry3d::Identity());

  // Links are numbered depth-first (parents first): assign each to a body.
  for (std::size_t i = 0; i < links.size(); ++i) {
    const int joint_index = links[i].parent_joint;
    const bool merge =
        joint_index >= 0 && merge_fixed_links && joints[joint_index].type == Joint::Type::kFixed;
    if (merge) {
      const int parent_link = joints[joint_index].parent_link;
      body_of_link_[i] = body_of_link_[parent_link];
      link_in_body_[i] = link_in_body_[parent_link] * joints[joint_index].origin;
      bodies_[body_of_link_[i]].links.push_back(static_cast<int>(i));
      continue;
    }
    RigidBody body;
    body.name = links[i].name;
    body.links.push_back(static_cast<int>(i));
    if (joint_index >= 0) {
      const Joint& joint = joints[joint_index];
      body.joint = joint_index;
      body.parent_body = body_of_link_[joint.parent_link];
      body.joint_pose_in_parent = link_in_body_[joint.parent_link] * joint.origin;
      body.joint_axis = joint.axis;
    }
    body_of_link_[i] = static_cast<int>(bodies_.size());
    bodies_.push_back(std::move(body));
  }

  // Composite mass, centre of mass and inertia of each body (parallel-axis theorem).
  for (auto& body : bodies_) set_composite_inertia(body, links, link_in_body_, source);

  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    servo_bodies_[servo] = body_of_link_[joints[model.servo_joint(servo)].child_link];
  }
}

}  // namespace upkie_rl
