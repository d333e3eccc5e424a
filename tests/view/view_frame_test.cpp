#include "view/view_frame.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "common/allocation_counter.hpp"

namespace upkie_rl {
namespace {

TEST(ViewFrame, FieldsNameEveryColumnAndCapTheActions) {
  const std::vector<std::string> fields = view_frame_fields({"ground_velocity"});
  ASSERT_EQ(fields.size(), view_frame_size(1));
  EXPECT_EQ(fields[kViewPitch], "pitch");
  EXPECT_EQ(fields[kViewBaseQz], "base_qz");
  EXPECT_EQ(fields[kViewFirstJoint], "left_hip");
  EXPECT_EQ(fields[kViewFirstJoint + 5], "right_wheel");
  EXPECT_EQ(fields[kViewFirstAction], "action.ground_velocity");
  const std::vector<std::string> many(20, "a");
  EXPECT_EQ(view_frame_fields(many).size(), view_frame_size(20));
  EXPECT_EQ(view_frame_size(20), kViewFirstAction + kMaxViewActions);
}

TEST(ViewFrame, WritesTheObservationWithoutAllocating) {
  Observation observation;
  observation.time = 1.25;
  observation.base_orientation.pitch = 0.1;
  observation.wheel_odometry.position = -0.3;
  observation.has_sim = true;
  observation.sim_base.position = Eigen::Vector3d(1.0, 2.0, 0.5);
  observation.sim_base.orientation = Eigen::Quaterniond(0.5, 0.5, 0.5, 0.5);
  for (std::size_t i = 0; i < kNumServos; ++i) observation.servo[i].position = 0.1 * double(i);
  const std::vector<float> action = {0.75f, -0.5f};
  std::vector<double> frame(view_frame_size(2));
  const std::size_t before = testing::this_thread_allocations;
  write_view_frame(observation, {3, 42, 17.5}, action, frame);
  EXPECT_EQ(testing::this_thread_allocations, before);
  EXPECT_EQ(frame[kViewEpisode], 3.0);
  EXPECT_EQ(frame[kViewStep], 42.0);
  EXPECT_EQ(frame[kViewTime], 1.25);
  EXPECT_EQ(frame[kViewReturn], 17.5);
  EXPECT_EQ(frame[kViewPitch], 0.1);
  EXPECT_EQ(frame[kViewGroundPosition], -0.3);
  EXPECT_EQ(frame[kViewBaseY], 2.0);
  EXPECT_EQ(frame[kViewBaseQw], 0.5);
  EXPECT_DOUBLE_EQ(frame[kViewFirstJoint + 4], 0.4);
  EXPECT_EQ(frame[kViewFirstAction], 0.75);
  EXPECT_EQ(frame[kViewFirstAction + 1], -0.5);
}

TEST(ViewFrame, ARealRobotHasNoGroundTruthPose) {
  Observation observation;
  observation.has_sim = false;
  std::vector<double> frame(view_frame_size(0));
  write_view_frame(observation, {}, {}, frame);
  EXPECT_TRUE(std::isnan(frame[kViewBaseX]));
  EXPECT_TRUE(std::isnan(frame[kViewBaseQz]));
  EXPECT_EQ(frame[kViewFirstJoint], 0.0);
}

}  // namespace
}  // namespace upkie_rl
