#include "sim/mass_properties.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>

namespace upkie_rl {
namespace {

/// Inertia of a point mass `mass` at `offset` from the axes' origin.
Eigen::Matrix3d point_inertia(double mass, const Eigen::Vector3d& offset) {
  return mass * (offset.squaredNorm() * Eigen::Matrix3d::Identity() - offset * offset.transpose());
}

}  // namespace

Eigen::Matrix3d MassProperties::inertia_in_body() const {
  const Eigen::Matrix3d axes = principal_frame.linear();
  return axes * principal_inertia.asDiagonal() * axes.transpose();
}

MassProperties with_point_mass(const MassProperties& body, double mass,
                               const Eigen::Vector3d& position) {
  MassProperties result;
  result.mass = body.mass + mass;
  const Eigen::Vector3d body_com = body.principal_frame.translation();
  const Eigen::Vector3d com = (body.mass * body_com + mass * position) / result.mass;
  // The tensor about the new centre of mass, in the body's principal axes.
  const Eigen::Matrix3d axes = body.principal_frame.linear();
  const Eigen::Matrix3d inertia = Eigen::Matrix3d(body.principal_inertia.asDiagonal()) +
                                  point_inertia(body.mass, axes.transpose() * (body_com - com)) +
                                  point_inertia(mass, axes.transpose() * (position - com));
  result.principal_frame.translation() = com;
  const Eigen::Matrix3d off_diagonal = inertia - Eigen::Matrix3d(inertia.diagonal().asDiagonal());
  if (off_diagonal.norm() <= 1e-12 * std::max(1e-12, inertia.norm())) {
    result.principal_frame.linear() = axes;
    result.principal_inertia = inertia.diagonal();
    return result;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(inertia);
  Eigen::Matrix3d eigenvectors = solver.eigenvectors();
  if (eigenvectors.determinant() < 0.0) eigenvectors.col(2) = -eigenvectors.col(2);
  result.principal_frame.linear() = axes * eigenvectors;
  result.principal_inertia = solver.eigenvalues();
  return result;
}

}  // namespace upkie_rl
