#include "spine/reset_config.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "message_builder.hpp"
#include "spine/spine_error.hpp"

namespace upkie_rl {
namespace {

TEST(ResetConfig, StartConfigCarriesTheResetState) {
  ResetState state;
  state.position_base_in_world = {0.1, -0.2, 0.7};
  state.orientation_base_in_world = Eigen::Quaterniond(0.8, 0.0, 0.6, 0.0);
  state.linear_velocity_base_to_world_in_world = {0.5, 0.0, -0.1};
  state.angular_velocity_base_in_base = {0.0, 0.3, 0.0};
  state.joint_configuration = {0.1, 0.2, 0.3, -0.1, -0.2, -0.3};
  msgpack::sbuffer buffer;
  write_start_config_msgpack(state, {}, buffer);
  Dictionary config;
  config.update(msgpack::unpack(buffer.data(), buffer.size()).get());

  const ResetState read = reset_state_from_config(config);
  EXPECT_EQ(read.position_base_in_world, state.position_base_in_world);
  EXPECT_TRUE(
      read.orientation_base_in_world.coeffs().isApprox(state.orientation_base_in_world.coeffs()));
  EXPECT_EQ(read.linear_velocity_base_to_world_in_world,
            state.linear_velocity_base_to_world_in_world);
  EXPECT_EQ(read.angular_velocity_base_in_base, state.angular_velocity_base_in_base);
  EXPECT_EQ(read.joint_configuration, state.joint_configuration);

  EXPECT_EQ(config.at("bullet").at("reset").at("orientation_base_in_world").kind(),
            Dictionary::Kind::kQuaternion);
  EXPECT_DOUBLE_EQ(config.at("bullet").at("torque_control").at("kp").as_number(), 20.0);
  EXPECT_DOUBLE_EQ(config.at("bullet").at("torque_control").at("kd").as_number(), 1.0);
  EXPECT_DOUBLE_EQ(config.at("wheel_odometry").at("signed_radius").at("left_wheel").as_number(),
                   0.05);
  EXPECT_DOUBLE_EQ(config.at("wheel_odometry").at("signed_radius").at("right_wheel").as_number(),
                   -0.05);
  EXPECT_EQ(config.at("base_orientation").at("rotation_base_to_imu").as_array(),
            (std::vector<double>{-1, 0, 0, 0, 1, 0, 0, 0, -1}));
  EXPECT_DOUBLE_EQ(config.at("floor_contact").at("upper_leg_torque_threshold").as_number(), 10.0);
  const Dictionary& wheel_contact = config.at("wheel_contact");
  EXPECT_DOUBLE_EQ(wheel_contact.at("cutoff_period").as_number(), 0.2);
  EXPECT_DOUBLE_EQ(wheel_contact.at("liftoff_inertia").as_number(), 0.001);
  EXPECT_DOUBLE_EQ(wheel_contact.at("min_touchdown_acceleration").as_number(), 2.0);
  EXPECT_DOUBLE_EQ(wheel_contact.at("min_touchdown_torque").as_number(), 0.015);
  EXPECT_DOUBLE_EQ(wheel_contact.at("touchdown_inertia").as_number(), 0.004);
  EXPECT_EQ(wheel_contact.at("touchdown_inertia").kind(), Dictionary::Kind::kFloat);
}

TEST(ResetConfig, MissingKeysKeepDefaults) {
  testing::MessageBuilder message;
  message.map(1).key("bullet").map(1).key("reset").map(1).key("position_base_in_world");
  message.array(3).real(0).real(0).real(1.0);
  Dictionary config;
  config.update(message.object().get());
  const ResetState read = reset_state_from_config(config);
  EXPECT_DOUBLE_EQ(read.position_base_in_world.z(), 1.0);
  EXPECT_TRUE(
      read.orientation_base_in_world.coeffs().isApprox(Eigen::Quaterniond::Identity().coeffs()));
  Dictionary empty;
  EXPECT_DOUBLE_EQ(reset_state_from_config(empty).position_base_in_world.z(), 0.6);
}

TEST(ResetConfig, BadValuesAreNamed) {
  const auto error_of = [](testing::MessageBuilder& message) -> std::string {
    Dictionary config;
    config.update(message.object().get());
    try {
      reset_state_from_config(config);
    } catch (const SpineError& error) {
      return error.what();
    }
    return "";
  };
  testing::MessageBuilder wrong_length;
  wrong_length.map(1).key("bullet").map(1).key("reset").map(1).key("joint_configuration");
  wrong_length.array(5).real(0).real(0).real(0).real(0).real(0);
  EXPECT_NE(error_of(wrong_length).find("joint_configuration' must be an array of 6"),
            std::string::npos);
  testing::MessageBuilder zero_quaternion;
  zero_quaternion.map(1).key("bullet").map(1).key("reset").map(1);
  zero_quaternion.key("orientation_base_in_world").array(4).real(0).real(0).real(0).real(0);
  EXPECT_NE(error_of(zero_quaternion).find("is zero"), std::string::npos);
  testing::MessageBuilder not_finite;
  not_finite.map(1).key("bullet").map(1).key("reset").map(1).key("position_base_in_world");
  not_finite.array(3).real(0).real(std::nan("")).real(0);
  EXPECT_NE(error_of(not_finite).find("non-finite"), std::string::npos);
}

TEST(ResetConfig, ServoGainsComeFromTorqueControl) {
  SpineStartParameters parameters;
  parameters.kp = 12.5;
  parameters.kd = 0.75;
  msgpack::sbuffer buffer;
  write_start_config_msgpack(ResetState{}, parameters, buffer);
  Dictionary config;
  config.update(msgpack::unpack(buffer.data(), buffer.size()).get());
  const ServoGains gains = servo_gains_from_config(config, ServoGains{20.0, 1.0});
  EXPECT_DOUBLE_EQ(gains.kp, 12.5);
  EXPECT_DOUBLE_EQ(gains.kd, 0.75);

  // Absent keys keep the defaults; an integer gain is a number too.
  testing::MessageBuilder only_kp;
  only_kp.map(1).key("bullet").map(1).key("torque_control").map(1).key("kp").integer(30);
  Dictionary partial;
  partial.update(only_kp.object().get());
  const ServoGains partial_gains = servo_gains_from_config(partial, ServoGains{20.0, 1.0});
  EXPECT_DOUBLE_EQ(partial_gains.kp, 30.0);
  EXPECT_DOUBLE_EQ(partial_gains.kd, 1.0);
  EXPECT_DOUBLE_EQ(servo_gains_from_config(Dictionary{}, ServoGains{3.0, 4.0}).kd, 4.0);
}

TEST(ResetConfig, BadServoGainsAreNamed) {
  const auto error_of = [](testing::MessageBuilder& message) -> std::string {
    Dictionary config;
    config.update(message.object().get());
    try {
      servo_gains_from_config(config, ServoGains{});
    } catch (const SpineError& error) {
      return error.what();
    }
    return "";
  };
  testing::MessageBuilder negative;
  negative.map(1).key("bullet").map(1).key("torque_control").map(1).key("kd").real(-1.0);
  EXPECT_NE(error_of(negative).find("'bullet.torque_control.kd' must be a finite non-negative"),
            std::string::npos);
  testing::MessageBuilder not_finite;
  not_finite.map(1).key("bullet").map(1).key("torque_control").map(1).key("kp");
  not_finite.real(std::numeric_limits<double>::infinity());
  EXPECT_NE(error_of(not_finite).find("torque_control.kp"), std::string::npos);
  testing::MessageBuilder text;
  text.map(1).key("bullet").map(1).key("torque_control").map(1).key("kp").string("high");
  EXPECT_NE(error_of(text).find("torque_control.kp"), std::string::npos);
  testing::MessageBuilder not_a_map;
  not_a_map.map(1).key("bullet").map(1).key("torque_control").real(1.0);
  EXPECT_NE(error_of(not_a_map).find("'bullet.torque_control' is not a map"), std::string::npos);
}

}  // namespace
}  // namespace upkie_rl

namespace upkie_rl {
namespace {

TEST(ImuUncertaintyFromConfig, ReadsThePublicSpineKeysAndRefusesBadOnes) {
  EXPECT_TRUE(imu_uncertainty_from_config(Dictionary{}).is_zero());
  testing::MessageBuilder message;
  message.map(1).key("bullet").map(1).key("imu_uncertainty").map(4);
  message.key("accelerometer_bias").array(3).real(0.1).real(-0.2).real(0.3);
  message.key("accelerometer_noise").real(0.05);
  message.key("gyroscope_bias").array(3).real(0.01).real(0.02).real(-0.03);
  message.key("gyroscope_noise").real(0.001);
  Dictionary config;
  config.update(message.object().get());
  const ImuUncertainty imu = imu_uncertainty_from_config(config);
  EXPECT_TRUE(imu.accelerometer_bias.isApprox(Eigen::Vector3d(0.1, -0.2, 0.3)));
  EXPECT_TRUE(imu.gyroscope_bias.isApprox(Eigen::Vector3d(0.01, 0.02, -0.03)));
  EXPECT_DOUBLE_EQ(imu.accelerometer_noise, 0.05);
  EXPECT_DOUBLE_EQ(imu.gyroscope_noise, 0.001);

  testing::MessageBuilder negative;
  negative.map(1).key("bullet").map(1).key("imu_uncertainty").map(1).key("gyroscope_noise");
  negative.real(-1.0);
  Dictionary bad;
  bad.update(negative.object().get());
  try {
    imu_uncertainty_from_config(bad);
    FAIL() << "a negative deviation passed";
  } catch (const SpineError& error) {
    EXPECT_NE(std::string(error.what()).find("bullet.imu_uncertainty.gyroscope_noise"),
              std::string::npos);
  }
  testing::MessageBuilder short_bias;
  short_bias.map(1).key("bullet").map(1).key("imu_uncertainty").map(1).key("gyroscope_bias");
  short_bias.array(2).real(0.0).real(0.0);
  Dictionary bad_bias;
  bad_bias.update(short_bias.object().get());
  EXPECT_THROW(imu_uncertainty_from_config(bad_bias), SpineError);
}

}  // namespace
}  // namespace upkie_rl
