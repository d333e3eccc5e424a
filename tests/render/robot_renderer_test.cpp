#include "render/robot_renderer.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <vector>

#include "render/render_error.hpp"

namespace upkie_rl {
namespace {

std::shared_ptr<const RobotModel> model() { return RobotModel::default_model(); }

/// Fraction of pixels whose RGB differ by more than 24 levels in some channel.
double changed_fraction(std::span<const std::uint8_t> a, std::span<const std::uint8_t> b) {
  std::size_t changed = 0;
  for (std::size_t i = 0; i + 2 < a.size(); i += 3) {
    for (int c = 0; c < 3; ++c) {
      if (std::abs(int(a[i + c]) - int(b[i + c])) > 24) {
        ++changed;
        break;
      }
    }
  }
  return static_cast<double>(changed) / static_cast<double>(a.size() / 3);
}

/// Changed fraction inside the centre box (a third of each side), where the tracked robot is.
double changed_in_centre(std::span<const std::uint8_t> a, std::span<const std::uint8_t> b,
                         int width, int height) {
  std::vector<std::uint8_t> centre_a, centre_b;
  for (int y = height / 3; y < 2 * height / 3; ++y) {
    const std::size_t start = (static_cast<std::size_t>(y) * width + width / 3) * 3;
    const std::size_t end = (static_cast<std::size_t>(y) * width + 2 * width / 3) * 3;
    centre_a.insert(centre_a.end(), a.begin() + start, a.begin() + end);
    centre_b.insert(centre_b.end(), b.begin() + start, b.begin() + end);
  }
  return changed_fraction(centre_a, centre_b);
}

TEST(RobotRenderer, FrameShowsTheRobotWhereItStands) {
  RenderConfig config;
  config.width = 320;
  config.height = 240;
  RobotRenderer renderer(model(), config);
  RobotPose standing;
  standing.base_position.z() = 0.56;
  const std::span<const std::uint8_t> frame = renderer.render(standing);
  ASSERT_EQ(frame.size(), 320u * 240u * 3u);
  const std::vector<std::uint8_t> with_robot(frame.begin(), frame.end());

  config.draw_robot = false;
  RobotRenderer empty_renderer(model(), config);
  const std::span<const std::uint8_t> empty = empty_renderer.render(standing);
  // The robot covers a good part of the centre of the frame, and little of the edges.
  EXPECT_GT(changed_in_centre(with_robot, empty, 320, 240), 0.1);
  EXPECT_LT(changed_fraction(with_robot, empty), 0.5);
}

TEST(RobotRenderer, FramesOfAFallingRobotDiffer) {
  RenderConfig config;
  config.width = 320;
  config.height = 240;
  RobotRenderer renderer(model(), config);
  RobotPose upright;
  upright.base_position.z() = 0.56;
  const std::span<const std::uint8_t> first = renderer.render(upright);
  const std::vector<std::uint8_t> upright_frame(first.begin(), first.end());
  RobotPose leaning = upright;
  leaning.base_orientation = Eigen::AngleAxisd(0.8, Eigen::Vector3d::UnitY());
  leaning.joint_angles[kLeftKnee] = 1.0;
  const std::span<const std::uint8_t> second = renderer.render(leaning);
  EXPECT_GT(changed_in_centre(upright_frame, second, 320, 240), 0.05);
  // Rendering is deterministic: the same pose gives the same pixels.
  const std::span<const std::uint8_t> again = renderer.render(upright);
  EXPECT_EQ(changed_fraction(upright_frame, again), 0.0);
}

TEST(RobotRenderer, OverlayTextIsDrawn) {
  RenderConfig config;
  config.width = 320;
  config.height = 240;
  RobotRenderer renderer(model(), config);
  const std::span<const std::uint8_t> plain = renderer.render(RobotPose{});
  const std::vector<std::uint8_t> plain_frame(plain.begin(), plain.end());
  const std::span<const std::uint8_t> texted = renderer.render(RobotPose{}, "time", "1.00 s");
  EXPECT_GT(changed_fraction(plain_frame, texted), 0.001);
}

TEST(RobotRenderer, BadSizesAndObservationsAreRefused) {
  RenderConfig config;
  config.width = 4000;
  EXPECT_THROW(RobotRenderer(model(), config), RenderError);
  Observation real_robot;
  real_robot.has_sim = false;
  EXPECT_THROW(robot_pose(real_robot), RenderError);
}

}  // namespace
}  // namespace upkie_rl
