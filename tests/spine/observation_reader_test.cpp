#include "spine/observation_reader.hpp"

#include <gtest/gtest.h>

#include "common/distinct_observation.hpp"
#include "message_builder.hpp"
#include "sim/observation_dict.hpp"
#include "spine/spine_error.hpp"

namespace upkie_rl {
namespace {

Observation sample_observation() {
  Observation observation;
  observation.time = 3.5;
  for (std::size_t i = 0; i < kNumServos; ++i) {
    observation.servo[i] = {0.1 + i, -0.5 * i, 0.25 * i, 42.0, 18.0};
  }
  observation.imu.orientation = Eigen::Quaterniond(0.9, 0.1, -0.2, 0.3).normalized();
  observation.imu.angular_velocity = {0.1, -0.2, 0.3};
  observation.imu.linear_acceleration = {1.0, 2.0, 3.0};
  observation.imu.raw_linear_acceleration = {1.0, 2.0, -6.81};
  observation.base_orientation.pitch = -0.12;
  observation.base_orientation.angular_velocity = {0.0, 1.5, 0.25};
  observation.base_orientation.rotation_base_to_world << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  observation.wheel_odometry = {0.75, -0.125};
  observation.floor_contact.contact = true;
  observation.has_sim = true;
  observation.sim_base.position = {1.0, -2.0, 0.5};
  observation.sim_base.orientation = Eigen::Quaterniond(0.5, 0.5, 0.5, 0.5);
  observation.sim_base.linear_velocity = {0.3, 0.2, 0.1};
  observation.sim_base.angular_velocity = {-0.3, -0.2, -0.1};
  return observation;
}

TEST(ObservationReader, RoundTripThroughTheSpineFormat) {
  const Observation written = sample_observation();
  msgpack::sbuffer buffer;
  write_observation_msgpack(written, buffer);
  const auto handle = msgpack::unpack(buffer.data(), buffer.size());
  Observation read;
  read_observation(handle.get(), read);
  EXPECT_DOUBLE_EQ(read.time, written.time);
  for (std::size_t i = 0; i < kNumServos; ++i) {
    EXPECT_DOUBLE_EQ(read.servo[i].position, written.servo[i].position);
    EXPECT_DOUBLE_EQ(read.servo[i].velocity, written.servo[i].velocity);
    EXPECT_DOUBLE_EQ(read.servo[i].torque, written.servo[i].torque);
    EXPECT_DOUBLE_EQ(read.servo[i].temperature, 42.0);
    EXPECT_DOUBLE_EQ(read.servo[i].voltage, 18.0);
  }
  EXPECT_TRUE(read.imu.orientation.coeffs().isApprox(written.imu.orientation.coeffs()));
  EXPECT_EQ(read.imu.angular_velocity, written.imu.angular_velocity);
  EXPECT_EQ(read.imu.linear_acceleration, written.imu.linear_acceleration);
  EXPECT_EQ(read.imu.raw_linear_acceleration, written.imu.raw_linear_acceleration);
  EXPECT_DOUBLE_EQ(read.base_orientation.pitch, -0.12);
  EXPECT_EQ(read.base_orientation.angular_velocity, written.base_orientation.angular_velocity);
  EXPECT_EQ(read.base_orientation.rotation_base_to_world,
            written.base_orientation.rotation_base_to_world);
  EXPECT_DOUBLE_EQ(read.wheel_odometry.position, 0.75);
  EXPECT_DOUBLE_EQ(read.wheel_odometry.velocity, -0.125);
  EXPECT_TRUE(read.floor_contact.contact);
  ASSERT_TRUE(read.has_sim);
  EXPECT_EQ(read.sim_base.position, written.sim_base.position);
  EXPECT_EQ(read.sim_base.orientation.coeffs(), written.sim_base.orientation.coeffs());
  EXPECT_EQ(read.sim_base.linear_velocity, written.sim_base.linear_velocity);
  EXPECT_EQ(read.sim_base.angular_velocity, written.sim_base.angular_velocity);
}

TEST(ObservationReader, WithoutSimSubtree) {
  Observation written = sample_observation();
  written.has_sim = false;
  msgpack::sbuffer buffer;
  write_observation_msgpack(written, buffer);
  Observation read;
  read.has_sim = true;
  read_observation(msgpack::unpack(buffer.data(), buffer.size()).get(), read);
  EXPECT_FALSE(read.has_sim);
}

std::string error_of(testing::MessageBuilder& message) {
  Observation observation;
  try {
    read_observation(message.object().get(), observation);
  } catch (const SpineError& error) {
    return error.what();
  }
  return "";
}

TEST(ObservationReader, NamesMissingAndMistypedKeys) {
  testing::MessageBuilder empty;
  empty.map(0);
  // The first required key of the declaration, in sorted order.
  EXPECT_NE(error_of(empty).find("'base_orientation' is missing"), std::string::npos)
      << error_of(empty);

  // Take a valid observation and break one value: a float replaced by a string.
  msgpack::sbuffer buffer;
  write_observation_msgpack(sample_observation(), buffer);
  auto handle = msgpack::unpack(buffer.data(), buffer.size());
  msgpack::object& root = const_cast<msgpack::object&>(handle.get());
  msgpack::object* pitch = nullptr;
  for (uint32_t i = 0; i < root.via.map.size; ++i) {
    if (root.via.map.ptr[i].key.as<std::string>() == "base_orientation") {
      pitch = &root.via.map.ptr[i].val.via.map.ptr[1].val;
    }
  }
  ASSERT_NE(pitch, nullptr);
  pitch->type = msgpack::type::NIL;
  Observation observation;
  try {
    read_observation(root, observation);
    FAIL();
  } catch (const SpineError& error) {
    EXPECT_NE(std::string(error.what()).find("'base_orientation.pitch' is not a number"),
              std::string::npos)
        << error.what();
  }
  testing::MessageBuilder not_a_map;
  not_a_map.array(0);
  EXPECT_NE(error_of(not_a_map).find("not a map"), std::string::npos);
}

/// The observation's dictionary without the key at the dotted `path`, as a msgpack object.
msgpack::object_handle without_key(const Observation& observation, const std::string& path) {
  nlohmann::json tree = observation_to_json(observation);
  nlohmann::json* map = &tree;
  std::string rest = path;
  for (std::size_t dot = rest.find('.'); dot != std::string::npos; dot = rest.find('.')) {
    map = &(*map)[rest.substr(0, dot)];
    rest = rest.substr(dot + 1);
  }
  EXPECT_EQ(map->erase(rest), 1u) << path;
  const std::vector<std::uint8_t> bytes = nlohmann::json::to_msgpack(tree);
  return msgpack::unpack(reinterpret_cast<const char*>(bytes.data()), bytes.size());
}

Observation distinct_observation() {
  Observation observation;
  testing::DistinctValueFiller filler;
  visit_observation_fields(observation, filler);
  return observation;
}

TEST(ObservationReader, EveryDeclaredFieldRoundTrips) {
  // Every field the declaration reads differs from its default, so a reader that skipped
  // one would leave a default the written dictionary does not have.
  const Observation written = distinct_observation();
  msgpack::sbuffer buffer;
  write_observation_msgpack(written, buffer);
  Observation read;
  read_observation(msgpack::unpack(buffer.data(), buffer.size()).get(), read);
  EXPECT_TRUE(read.has_sim);
  EXPECT_EQ(observation_to_json(read), observation_to_json(written));
}

TEST(ObservationReader, RefusesEachMissingRequiredKeyAndAcceptsEachMissingOptionalOne) {
  const Observation written = distinct_observation();
  int required = 0;
  for (const ObservationKey& key : observation_keys()) {
    const msgpack::object_handle message = without_key(written, key.path);
    Observation read = written;
    if (key.required) {
      ++required;
      try {
        read_observation(message.get(), read);
        ADD_FAILURE() << key.path << " is required but a message without it was read";
      } catch (const SpineError& error) {
        EXPECT_NE(std::string(error.what()).find("'" + key.path + "' is missing"),
                  std::string::npos)
            << error.what();
      }
    } else {
      // An absent optional key leaves its field as it was; without `sim`, has_sim is false.
      EXPECT_NO_THROW(read_observation(message.get(), read)) << key.path;
      if (key.path == "sim") {
        EXPECT_FALSE(read.has_sim);
      } else {
        EXPECT_EQ(observation_to_json(read), observation_to_json(written)) << key.path;
      }
    }
  }
  // Leaves: position, velocity and torque of six joints, pitch and angular velocity, the
  // odometry's two, sim.base.position. Maps: base_orientation, servo and its six joints,
  // sim.base, wheel_odometry.
  EXPECT_EQ(required, (3 * 6 + 2 + 2 + 1) + (1 + 1 + 6 + 1 + 1));
}

}  // namespace
}  // namespace upkie_rl
