#pragma once
/// @file
/// RobotRenderer: draws Upkie from its ground truth (base pose and joint angles) with
/// MuJoCo's renderer, offscreen, whatever backend simulated it.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "model/robot_model.hpp"
#include "sim/floor_bumps.hpp"
#include "sim/observation.hpp"

namespace upkie_rl {

/// What a frame shows of the robot.
struct RobotPose {
  Eigen::Vector3d base_position = Eigen::Vector3d(0.0, 0.0, 0.6);  ///< World frame [m].
  Eigen::Quaterniond base_orientation = Eigen::Quaterniond::Identity();
  std::array<double, kNumServos> joint_angles{};  ///< Standard order [rad].
};

/// The pose in a simulated observation's ground truth.
/// @throws RenderError when the observation has none (a real robot's).
RobotPose robot_pose(const Observation& observation);

/// Frame sizes RenderConfig::validate accepts [px].
inline constexpr int kMinFrameWidth = 16;
inline constexpr int kMaxFrameWidth = 1920;
inline constexpr int kMinFrameHeight = 16;
inline constexpr int kMaxFrameHeight = 1080;

/// Font scale [%] of the caption on frames of `height` rows: 150 at 480 rows, in proportion,
/// in MuJoCo's steps (50 to 300), so that the caption takes the same share of any frame.
int overlay_font_scale(int height);

/// Image size and camera. The camera tracks the base from a fixed direction.
struct RenderConfig {
  int width = 640;                  ///< [px], in [kMinFrameWidth, kMaxFrameWidth].
  int height = 480;                 ///< [px], in [kMinFrameHeight, kMaxFrameHeight].
  double camera_distance = 1.4;     ///< From the tracked point [m].
  double camera_azimuth = 135.0;    ///< [deg], MuJoCo's convention.
  double camera_elevation = -20.0;  ///< [deg], negative looks down.
  bool draw_robot = true;           ///< False draws the empty scene (floor, light).
  FloorBumps bumps{};               ///< Drawn on the floor, as the simulation had them.

  /// @throws RenderError naming a size or a bump setting out of range.
  void validate() const;
};

/// Renders frames of one robot. Owns an OpenGL context current on the thread that made it:
/// use it from that thread only.
class RobotRenderer {
 public:
  /// @throws RenderError when OpenGL or the model cannot be set up.
  explicit RobotRenderer(std::shared_ptr<const RobotModel> model, const RenderConfig& config = {});
  ~RobotRenderer();
  RobotRenderer(const RobotRenderer&) = delete;
  RobotRenderer& operator=(const RobotRenderer&) = delete;

  /// Draws `pose` with a caption in the top left corner, `titles` and `values` being two
  /// columns of lines ("time\npitch", "1.00 s\n+0.01 rad"), and returns the frame: height
  /// rows of width RGB pixels, top row first. Valid until the next call.
  std::span<const std::uint8_t> render(const RobotPose& pose, const std::string& titles = {},
                                       const std::string& values = {});

  int width() const { return config_.width; }
  int height() const { return config_.height; }

 private:
  struct Impl;
  RenderConfig config_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace upkie_rl
