#include "render/robot_renderer.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "render/offscreen_context.hpp"
#include "render/render_error.hpp"
#include "sim/mujoco_model.hpp"

namespace upkie_rl {

RobotPose robot_pose(const Observation& observation) {
  if (!observation.has_sim) {
    throw RenderError("cannot render an observation without ground truth (a real robot's)");
  }
  RobotPose pose;
  pose.base_position = observation.sim_base.position;
  pose.base_orientation = observation.sim_base.orientation;
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    pose.joint_angles[servo] = observation.servo[servo].position;
  }
  return pose;
}

int overlay_font_scale(int height) {
  // 150 % at 480 rows, proportional, in MuJoCo's steps of 50 % (mjFONTSCALE_50 to _300),
  // rounded down: a caption a little small hides less of a small frame.
  const int steps = static_cast<int>(std::floor(height * 150.0 / 480.0 / 50.0 + 1e-9));
  return 50 * std::clamp(steps, 1, 6);
}

void RenderConfig::validate() const {
  if (width < kMinFrameWidth || width > kMaxFrameWidth || height < kMinFrameHeight ||
      height > kMaxFrameHeight) {
    throw RenderError("frame size must be within " + std::to_string(kMinFrameWidth) + "x" +
                      std::to_string(kMinFrameHeight) + " and " + std::to_string(kMaxFrameWidth) +
                      "x" + std::to_string(kMaxFrameHeight) + " pixels, got " +
                      std::to_string(width) + "x" + std::to_string(height));
  }
  if (!(camera_distance > 0.0) || !std::isfinite(camera_distance)) {
    throw RenderError("camera distance must be positive");
  }
  try {
    bumps.validate("render: ");
  } catch (const std::invalid_argument& error) {
    throw RenderError(error.what());
  }
}

namespace {

/// The scene's world: the simulation's floor and bumps.
MujocoConfig scene_config(const RenderConfig& config) {
  MujocoConfig scene;
  scene.bumps = config.bumps;
  return scene;
}

}  // namespace

struct RobotRenderer::Impl {
  OffscreenContext context;
  std::shared_ptr<const MujocoModel> scene_model;
  MujocoDataPtr data;
  mjvScene scene{};
  mjvCamera camera{};
  mjvOption option{};
  mjrContext render_context{};
  std::vector<std::uint8_t> bottom_up;
  std::vector<std::uint8_t> frame;

  Impl(const RobotModel& robot, const RenderConfig& config)
      : context(config.width, config.height),
        scene_model(build_mujoco_model(robot, scene_config(config))),
        data(mj_makeData(scene_model->model.get())) {
    const mjModel* m = scene_model->model.get();
    mjv_defaultScene(&scene);
    mjv_defaultCamera(&camera);
    mjv_defaultOption(&option);
    mjr_defaultContext(&render_context);
    mjv_makeScene(m, &scene, 1000);
    mjr_makeContext(m, &render_context, overlay_font_scale(config.height));
    if (render_context.offFBO == 0) {
      mjv_freeScene(&scene);
      mjr_freeContext(&render_context);
      throw RenderError("MuJoCo could not create its offscreen framebuffer in its EGL context");
    }
    mjr_setBuffer(mjFB_OFFSCREEN, &render_context);
    // The robot's geoms are in group 0, the floor in group 2 (see build_mujoco_model).
    option.geomgroup[0] = config.draw_robot ? 1 : 0;
    camera.type = mjCAMERA_TRACKING;
    camera.trackbodyid = scene_model->index.root_body;
    camera.distance = config.camera_distance;
    camera.azimuth = config.camera_azimuth;
    camera.elevation = config.camera_elevation;
    const std::size_t size = static_cast<std::size_t>(config.width) * config.height * 3;
    bottom_up.resize(size);
    frame.resize(size);
  }

  ~Impl() {
    mjv_freeScene(&scene);
    mjr_freeContext(&render_context);
  }
};

RobotRenderer::RobotRenderer(std::shared_ptr<const RobotModel> model, const RenderConfig& config)
    : config_(config) {
  config_.validate();
  impl_ = std::make_unique<Impl>(*model, config_);
}

RobotRenderer::~RobotRenderer() = default;

std::span<const std::uint8_t> RobotRenderer::render(const RobotPose& pose,
                                                    const std::string& titles,
                                                    const std::string& values) {
  Impl& impl = *impl_;
  impl.context.make_current();
  const mjModel* m = impl.scene_model->model.get();
  mjData* d = impl.data.get();
  const MujocoRobotIndex& index = impl.scene_model->index;
  mjtNum* root = d->qpos + index.root_qpos;
  const Eigen::Quaterniond orientation = pose.base_orientation.normalized();
  for (int i = 0; i < 3; ++i) root[i] = pose.base_position[i];
  root[3] = orientation.w();
  root[4] = orientation.x();
  root[5] = orientation.y();
  root[6] = orientation.z();
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    d->qpos[index.servo_qpos[servo]] = pose.joint_angles[servo];
  }
  mj_kinematics(m, d);
  mj_comPos(m, d);  // the tracking camera aims at the subtree's centre of mass

  mjv_updateScene(m, d, &impl.option, nullptr, &impl.camera, mjCAT_ALL, &impl.scene);
  const mjrRect viewport{0, 0, config_.width, config_.height};
  mjr_render(viewport, &impl.scene, &impl.render_context);
  if (!titles.empty()) {
    mjr_overlay(mjFONT_NORMAL, mjGRID_TOPLEFT, viewport, titles.c_str(), values.c_str(),
                &impl.render_context);
  }
  mjr_readPixels(impl.bottom_up.data(), nullptr, viewport, &impl.render_context);
  // OpenGL's rows start at the bottom; images start at the top.
  const std::size_t row = static_cast<std::size_t>(config_.width) * 3;
  for (int y = 0; y < config_.height; ++y) {
    std::memcpy(impl.frame.data() + y * row, impl.bottom_up.data() + (config_.height - 1 - y) * row,
                row);
  }
  return impl.frame;
}

}  // namespace upkie_rl
