#include "model/robot_model.hpp"

#include <gtest/gtest.h>

#include <fstream>

namespace upkie_rl {
namespace {

const RobotModel& model() { return *RobotModel::default_model(); }

std::filesystem::path write_temp(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / name;
  std::ofstream(path) << text;
  return path;
}

std::string shipped_urdf() {
  std::ifstream file(RobotModel::default_urdf_path());
  return std::string(std::istreambuf_iterator<char>(file), {});
}

TEST(RobotModelTest, MassMatchesDescription) {
  EXPECT_NEAR(model().total_mass(), 5.33922, 1e-4);
  EXPECT_EQ(model().links().size(), 41u);
}

TEST(RobotModelTest, WheelFacts) {
  EXPECT_DOUBLE_EQ(model().wheel_radius(), 0.05);
  EXPECT_NEAR(model().track(), 0.3048, 1e-3);
  EXPECT_TRUE(model().left_wheeled());
}

TEST(RobotModelTest, WheelGeometryMapsBaseVelocitiesToWheelSpeeds) {
  const WheelGeometry wheels = model().wheel_geometry();
  const WheelVelocities forward = wheels.velocities(1.0, 0.0);
  EXPECT_DOUBLE_EQ(forward.left, 1.0 / 0.05);  // the left wheel turns forward
  EXPECT_DOUBLE_EQ(forward.right, -1.0 / 0.05);
  // Counter-clockwise: the right wheel rolls forward (negative), the left one backward.
  const WheelVelocities turn = wheels.velocities(0.0, 1.0);
  EXPECT_DOUBLE_EQ(turn.left, -0.5 * model().track() / 0.05);
  EXPECT_DOUBLE_EQ(turn.right, turn.left);
  const WheelVelocities both = wheels.velocities(0.5, -2.0);
  EXPECT_DOUBLE_EQ(both.left, 0.5 / 0.05 + 2.0 * 0.5 * model().track() / 0.05);
  EXPECT_DOUBLE_EQ(both.right, -0.5 / 0.05 + 2.0 * 0.5 * model().track() / 0.05);
  // Back from the wheels: the forward part returns, the turn cancels out.
  EXPECT_NEAR(wheels.forward_motion(both.left, both.right), 0.5, 1e-12);
  EXPECT_NEAR(wheels.forward_motion(turn.left, turn.right), 0.0, 1e-12);
}

TEST(RobotModelTest, JointsInStandardOrderWithLimits) {
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    EXPECT_EQ(model().joints()[model().servo_joint(servo)].name, kServoNames[servo]);
  }
  EXPECT_DOUBLE_EQ(model().servo_limits(kLeftHip).lower, -1.26);
  EXPECT_DOUBLE_EQ(model().servo_limits(kRightHip).upper, 1.26);
  EXPECT_DOUBLE_EQ(model().servo_limits(kLeftKnee).upper, 2.51);
  EXPECT_DOUBLE_EQ(model().servo_limits(kLeftKnee).effort, 16.0);
  EXPECT_DOUBLE_EQ(model().servo_limits(kRightWheel).effort, 1.7);
  EXPECT_DOUBLE_EQ(model().servo_limits(kRightWheel).velocity, 111.0);
  EXPECT_FALSE(model().servo_limits(kLeftWheel).has_position_limits());
  EXPECT_TRUE(model().servo_limits(kLeftHip).has_position_limits());
}

TEST(RobotModelTest, KeyPositionsAtZero) {
  const auto poses = model().link_poses_at_zero();
  auto position = [&](const std::string& name) {
    return poses[*model().find_link(name)].translation();
  };
  EXPECT_TRUE(position("left_wheel_tire").isApprox(Eigen::Vector3d(0, 0.1524, -0.507), 1e-3));
  EXPECT_TRUE(position("right_wheel_tire").isApprox(Eigen::Vector3d(0, -0.1524, -0.507), 1e-3));
  EXPECT_NEAR(position("left_knee_qdd100_rotor").z(), -0.332, 1e-3);
  EXPECT_NEAR(std::abs(position("left_knee_qdd100_rotor").y()), 0.2104, 1e-3);
  EXPECT_NEAR(position("left_hip_qdd100_rotor").z(), -0.164, 1e-3);
}

TEST(RobotModelTest, ImuMounting) {
  const Eigen::Matrix3d expected = Eigen::Vector3d(-1.0, 1.0, -1.0).asDiagonal();
  EXPECT_TRUE(model().rotation_base_to_imu().isApprox(expected, 1e-9));
  EXPECT_TRUE(model().imu_position_in_base().isApprox(Eigen::Vector3d(0, 0, -0.1), 1e-12));
}

TEST(RobotModelTest, TireContactParameters) {
  const Link& tire = model().links()[*model().find_link("left_wheel_tire")];
  EXPECT_DOUBLE_EQ(tire.contact.lateral_friction, 1.0);
  EXPECT_DOUBLE_EQ(tire.contact.rolling_friction, 0.01);
  EXPECT_DOUBLE_EQ(tire.contact.stiffness, 30000.0);
  EXPECT_DOUBLE_EQ(tire.contact.damping, 1000.0);
  const Link& torso = model().links()[*model().find_link("torso")];
  EXPECT_DOUBLE_EQ(torso.contact.lateral_friction, 0.5);
  EXPECT_FALSE(torso.contact.is_soft());
}

void expect_model_error(const std::filesystem::path& path, const std::string& fragment) {
  try {
    RobotModel::from_urdf_file(path);
    FAIL() << "expected ModelError containing '" << fragment << "'";
  } catch (const ModelError& error) {
    EXPECT_NE(std::string(error.what()).find(fragment), std::string::npos) << error.what();
  }
}

TEST(RobotModelTest, MissingFileIsNamed) {
  expect_model_error("/nonexistent/upkie.urdf", "/nonexistent/upkie.urdf");
}

TEST(RobotModelTest, MalformedXmlGivesFileAndLine) {
  const auto path =
      write_temp("upkie_rl_malformed.urdf", "<robot name='x'>\n<link name='a'>\n</robot>");
  expect_model_error(path, "upkie_rl_malformed.urdf:");
}

TEST(RobotModelTest, MissingServoJointIsNamed) {
  std::string xml = shipped_urdf();
  const std::string from = "joint name=\"right_knee\"";
  xml.replace(xml.find(from), from.size(), "joint name=\"right_knee_renamed\"");
  expect_model_error(write_temp("upkie_rl_no_knee.urdf", xml), "right_knee");
}

TEST(RobotModelTest, BadContactValueNamesLink) {
  std::string xml = shipped_urdf();
  const std::string from = "<stiffness value=\"30000\"/>";
  xml.replace(xml.find(from), from.size(), "<stiffness value=\"soft\"/>");
  expect_model_error(write_temp("upkie_rl_bad_contact.urdf", xml), "left_wheel_tire");
}

TEST(RobotModelTest, UrdfdomErrorNamesElement) {
  std::string xml = shipped_urdf();
  const std::string from = "<child link=\"left_femur\"/>";
  xml.replace(xml.find(from), from.size(), "<child link=\"left_thigh\"/>");
  expect_model_error(write_temp("upkie_rl_bad_child.urdf", xml), "left_thigh");
}

}  // namespace
}  // namespace upkie_rl
