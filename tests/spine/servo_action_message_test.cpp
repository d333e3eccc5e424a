#include "spine/servo_action_message.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "message_builder.hpp"
#include "spine/spine_error.hpp"

namespace upkie_rl {
namespace {

TEST(ServoActionMessage, RoundTripThroughTheDictionary) {
  ServoAction action;
  for (std::size_t i = 0; i < kNumServos; ++i) {
    action[i] = ServoCommand{0.1 * i, 2.0 * i, 0.5, 1.0, 0.0, 1.5};
  }
  action[kLeftWheel].position = std::nan("");
  msgpack::sbuffer buffer;
  write_servo_action_msgpack(action, buffer);
  Dictionary dictionary;
  dictionary.update(msgpack::unpack(buffer.data(), buffer.size()).get());
  // Every value is a float64 on the wire, even the integral ones.
  for (const auto& joint : kServoNames) {
    for (const char* field :
         {"position", "velocity", "feedforward_torque", "kp_scale", "kd_scale", "maximum_torque"}) {
      EXPECT_EQ(dictionary.at("servo").at(joint).at(field).kind(), Dictionary::Kind::kFloat)
          << joint << "." << field;
    }
  }
  ServoAction read = spine_default_servo_action();
  read_servo_action(dictionary, read);
  for (std::size_t i = 0; i < kNumServos; ++i) {
    if (i == kLeftWheel) {
      EXPECT_TRUE(std::isnan(read[i].position));
    } else {
      EXPECT_DOUBLE_EQ(read[i].position, 0.1 * i);
    }
    EXPECT_DOUBLE_EQ(read[i].velocity, 2.0 * i);
    EXPECT_DOUBLE_EQ(read[i].feedforward_torque, 0.5);
    EXPECT_DOUBLE_EQ(read[i].kp_scale, 1.0);
    EXPECT_DOUBLE_EQ(read[i].kd_scale, 0.0);
    EXPECT_DOUBLE_EQ(read[i].maximum_torque, 1.5);
  }
}

TEST(ServoActionMessage, SpineDefaults) {
  for (const ServoCommand& command : spine_default_servo_action()) {
    EXPECT_TRUE(std::isnan(command.position));
    EXPECT_EQ(command.velocity, 0.0);
    EXPECT_EQ(command.feedforward_torque, 0.0);
    EXPECT_EQ(command.kp_scale, 1.0);
    EXPECT_EQ(command.kd_scale, 1.0);
    EXPECT_EQ(command.maximum_torque, 1.0);
  }
}

TEST(ServoActionMessage, MaximumTorqueAboveEffortIsAnError) {
  const std::array<double, kNumServos> efforts = {16.0, 16.0, 1.7, 16.0, 16.0, 1.7};
  testing::MessageBuilder message = testing::servo_field("right_wheel", "maximum_torque");
  message.real(2.0);
  Dictionary dictionary;
  dictionary.update(message.object().get());
  ServoAction action = spine_default_servo_action();
  EXPECT_NO_THROW(read_servo_action(dictionary, action));  // not checked without limits
  try {
    read_servo_action(dictionary, action, &efforts);
    FAIL();
  } catch (const SpineError& error) {
    EXPECT_NE(std::string(error.what()).find("right_wheel.maximum_torque"), std::string::npos);
  }
}

TEST(ServoActionMessage, NonNumbersAreErrors) {
  testing::MessageBuilder message = testing::servo_field("left_hip", "velocity");
  message.string("fast");
  Dictionary dictionary;
  dictionary.update(message.object().get());
  ServoAction action{};
  EXPECT_THROW(read_servo_action(dictionary, action), SpineError);
}

}  // namespace
}  // namespace upkie_rl
