#include "envs/records/episode_recorder.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "common/csv_fields.hpp"
#include "common/temp_files.hpp"
#include "envs/registry/env_factory.hpp"

namespace upkie_rl {
namespace {

// The columns after the step's outcome are the declared ones (envs/records/record_columns.hpp), in
// their order, and each holds the field the declaration names.
TEST(EpisodeRecorder, WritesTheDeclaredColumnsWithTheirFields) {
  auto env = make_env("Upkie-Bullet-Pendulum");
  const auto path = testing::temp_path("declared_columns.csv");
  std::vector<float> observation(env->observation_space().size());
  std::vector<float> action(env->action_space().size(), 0.0f);
  Observation at_reset;
  {
    EpisodeRecorder recorder(path);
    recorder.write_header(*env);
    env->reset(7, observation);
    ASSERT_NE(env->full_observation(), nullptr);
    ASSERT_TRUE(env->full_observation()->has_sim);
    at_reset = *env->full_observation();
    recorder.before_step(*env, observation);
    recorder.after_step(0, 0, action, env->step(action, observation));
    recorder.close();
  }
  std::ifstream in(path);
  std::string header_line;
  std::string row_line;
  ASSERT_TRUE(std::getline(in, header_line) && std::getline(in, row_line));
  const std::vector<std::string> header = testing::csv_fields(header_line);
  const std::vector<std::string> row = testing::csv_fields(row_line);
  ASSERT_EQ(row.size(), header.size());
  EXPECT_EQ(header[0], kEpisodeColumn);
  EXPECT_EQ(header[2], kTimeColumn);

  // Walk the declaration over the header's tail and over the pose the recorder saw.
  std::size_t column = 0;
  while (column < header.size() && header[column] != kTruncatedColumn) ++column;
  ASSERT_LT(column, header.size());
  ++column;
  RecordedPose pose;
  RecordedMeasurement measurement;
  std::vector<std::string> declared;
  const auto collect = [&](auto name, auto&) { declared.emplace_back(name); };
  visit_pose_columns(pose, collect);
  visit_measurement_columns(measurement, collect);
  ASSERT_EQ(header.size() - column, declared.size());
  for (std::size_t i = 0; i < declared.size(); ++i) EXPECT_EQ(header[column + i], declared[i]);

  // Recorded before the step: the ground truth and measurements of the reset.
  RecordedPose expected_pose;
  expected_pose.base_position = at_reset.sim_base.position;
  expected_pose.base_orientation = at_reset.sim_base.orientation;
  for (std::size_t i = 0; i < kNumServos; ++i) {
    expected_pose.joint_angles[i] = at_reset.servo[i].position;
  }
  const RecordedMeasurement expected_measurement{at_reset.base_orientation.pitch,
                                                 at_reset.wheel_odometry.position};
  std::size_t value = column;
  const auto compare = [&](auto name, const double& expected) {
    EXPECT_NEAR(std::stod(row[value++]), expected, 1e-6) << name;
  };
  visit_pose_columns(expected_pose, compare);
  visit_measurement_columns(expected_measurement, compare);
  EXPECT_GT(expected_pose.base_position.z(), 0.3);  // a standing robot, not zeros
}

}  // namespace
}  // namespace upkie_rl
