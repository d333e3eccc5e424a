#pragma once
/// @file
/// MassProperties: the mass, centre of mass and principal inertia of a rigid body, and the
/// body with a point mass (a payload) attached to it.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace upkie_rl {

/// Mass properties of one rigid body, in a frame of the body (its link frame).
struct MassProperties {
  double mass = 0.0;  ///< [kg]
  /// Principal inertial frame in the body frame: origin at the centre of mass, axes the
  /// principal axes.
  Eigen::Isometry3d principal_frame = Eigen::Isometry3d::Identity();
  /// Moments of inertia about the principal axes [kg.m^2].
  Eigen::Vector3d principal_inertia = Eigen::Vector3d::Zero();

  /// Inertia tensor about the centre of mass, in the body frame's axes [kg.m^2].
  Eigen::Matrix3d inertia_in_body() const;
};

/// `body` with a point mass of `mass` [kg] rigidly attached at `position` [m] (body frame):
/// mass added, centre of mass moved to the barycentre, and inertia about it by the parallel
/// axis theorem, diagonalised. The principal axes stay those of `body` when they are still
/// principal (the point mass lies on one of them through the new centre of mass).
MassProperties with_point_mass(const MassProperties& body, double mass,
                               const Eigen::Vector3d& position);

}  // namespace upkie_rl
