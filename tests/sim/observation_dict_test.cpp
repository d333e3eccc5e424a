#include "sim/observation_dict.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

namespace upkie_rl {
namespace {

Observation make_observation(bool has_sim) {
  Observation observation;
  observation.time = 1.25;
  for (std::size_t i = 0; i < kNumServos; ++i) {
    observation.servo[i] = {0.1 * i, -0.2 * i, 0.3 + i, 42.0, 18.0};
  }
  observation.imu.orientation = Eigen::Quaterniond(0.5, 0.5, -0.5, 0.5);
  observation.imu.angular_velocity = {1.0, 2.0, 3.0};
  observation.imu.linear_acceleration = {0.1, 0.2, 0.3};
  observation.imu.raw_linear_acceleration = {0.1, 0.2, -9.5};
  observation.base_orientation.pitch = 0.05;
  observation.base_orientation.angular_velocity = {0.0, 0.7, 0.0};
  observation.base_orientation.rotation_base_to_world << 1, 2, 3, 4, 5, 6, 7, 8, 9;
  observation.wheel_odometry = {0.4, -0.6};
  observation.floor_contact.contact = true;
  observation.has_sim = has_sim;
  observation.sim_base.position = {0.1, 0.2, 0.55};
  observation.sim_base.orientation = Eigen::Quaterniond(0.9, 0.1, 0.3, 0.2).normalized();
  observation.sim_base.linear_velocity = {0.01, 0.02, 0.03};
  observation.sim_base.angular_velocity = {0.4, 0.5, 0.6};
  return observation;
}

std::set<std::string> leaf_keys(const nlohmann::json& tree, const std::string& prefix = "") {
  std::set<std::string> keys;
  for (const auto& [key, value] : tree.items()) {
    const std::string path = prefix.empty() ? key : prefix + "." + key;
    if (value.is_object()) {
      keys.merge(leaf_keys(value, path));
    } else {
      keys.insert(path);
    }
  }
  return keys;
}

/// Converts a decoded msgpack tree to JSON, checking the wire typing on the way: sorted
/// string keys, float64 for every real, never float32 or nil.
nlohmann::json checked_to_json(const msgpack::object& object, const std::string& path) {
  switch (object.type) {
    case msgpack::type::MAP: {
      nlohmann::json tree = nlohmann::json::object();
      std::string previous;
      for (uint32_t i = 0; i < object.via.map.size; ++i) {
        const auto& pair = object.via.map.ptr[i];
        EXPECT_EQ(pair.key.type, msgpack::type::STR) << path;
        const std::string key = pair.key.as<std::string>();
        EXPECT_LT(previous, key) << "keys not sorted under " << path;
        previous = key;
        tree[key] = checked_to_json(pair.val, path + "." + key);
      }
      return tree;
    }
    case msgpack::type::ARRAY: {
      nlohmann::json array = nlohmann::json::array();
      for (uint32_t i = 0; i < object.via.array.size; ++i) {
        array.push_back(checked_to_json(object.via.array.ptr[i], path));
      }
      return array;
    }
    case msgpack::type::FLOAT64:
      return object.via.f64;
    case msgpack::type::BOOLEAN:
      return object.via.boolean;
    case msgpack::type::POSITIVE_INTEGER:
      EXPECT_TRUE(path.ends_with(".fault") || path.ends_with(".mode")) << path;
      return object.via.u64;
    default:
      ADD_FAILURE() << "unexpected msgpack type " << static_cast<int>(object.type) << " at "
                    << path;
      return nullptr;
  }
}

TEST(ObservationDict, JsonHasTheSpineKeys) {
  const auto keys = leaf_keys(observation_to_json(make_observation(true)));
  std::set<std::string> expected = {
      "time",
      "imu.orientation",
      "imu.angular_velocity",
      "imu.linear_acceleration",
      "imu.raw_angular_velocity",
      "imu.raw_linear_acceleration",
      "base_orientation.pitch",
      "base_orientation.angular_velocity",
      "base_orientation.rotation_base_to_world",
      "floor_contact.contact",
      "floor_contact.upper_leg_torque",
      "wheel_odometry.position",
      "wheel_odometry.velocity",
      "sim.base.position",
      "sim.base.orientation",
      "sim.base.linear_velocity",
      "sim.base.angular_velocity",
      "sim.imu.linear_velocity",
  };
  for (const char* wheel : {"left_wheel", "right_wheel"}) {
    for (const char* field : {"abs_acceleration", "abs_torque", "contact", "inertia"}) {
      expected.insert(std::string("floor_contact.") + wheel + "." + field);
    }
  }
  for (const auto& joint : kServoNames) {
    for (const char* field : {"position", "velocity", "torque", "temperature", "voltage",
                              "d_current", "q_current", "fault", "mode"}) {
      expected.insert("servo." + std::string(joint) + "." + field);
    }
  }
  EXPECT_EQ(keys, expected);
}

TEST(ObservationDict, SimSubtreeOnlyWithGroundTruth) {
  EXPECT_TRUE(observation_to_json(make_observation(true)).contains("sim"));
  EXPECT_FALSE(observation_to_json(make_observation(false)).contains("sim"));
}

TEST(ObservationDict, JsonValuesAndLayout) {
  const auto tree = observation_to_json(make_observation(true));
  EXPECT_DOUBLE_EQ(tree["time"].get<double>(), 1.25);
  EXPECT_DOUBLE_EQ(tree["servo"]["right_knee"]["torque"].get<double>(), 4.3);
  EXPECT_DOUBLE_EQ(tree["servo"]["left_knee"]["position"].get<double>(), 0.1);
  EXPECT_EQ(tree["servo"]["left_hip"]["mode"].get<int>(), kServoModePosition);
  // Quaternion [w, x, y, z] and matrix row-major.
  EXPECT_EQ(tree["imu"]["orientation"].get<std::vector<double>>(),
            (std::vector<double>{0.5, 0.5, -0.5, 0.5}));
  EXPECT_EQ(tree["base_orientation"]["rotation_base_to_world"].get<std::vector<double>>(),
            (std::vector<double>{1, 2, 3, 4, 5, 6, 7, 8, 9}));
  EXPECT_EQ(tree["floor_contact"]["contact"].get<bool>(), true);
  EXPECT_DOUBLE_EQ(tree["floor_contact"]["right_wheel"]["abs_torque"].get<double>(), 5.3);
  const double expected_leg_torque =
      std::sqrt(0.3 * 0.3 + 1.3 * 1.3 + 3.3 * 3.3 + 4.3 * 4.3);  // hips and knees
  EXPECT_NEAR(tree["floor_contact"]["upper_leg_torque"].get<double>(), expected_leg_torque, 1e-12);
  EXPECT_EQ(tree["imu"]["raw_angular_velocity"], tree["imu"]["angular_velocity"]);
}

TEST(ObservationDict, MsgpackRoundTripMatchesJson) {
  for (bool has_sim : {true, false}) {
    const Observation observation = make_observation(has_sim);
    msgpack::sbuffer buffer;
    write_observation_msgpack(observation, buffer);
    const msgpack::object_handle handle = msgpack::unpack(buffer.data(), buffer.size());
    ASSERT_EQ(handle.get().type, msgpack::type::MAP);
    EXPECT_EQ(checked_to_json(handle.get(), ""), observation_to_json(observation));
  }
}

TEST(ObservationDict, RealsAreFloat64OnTheWire) {
  Observation observation = make_observation(true);
  // Integral: msgpack-cxx's pack_double would write an integer; exact in float32 too.
  observation.time = 2.0;
  msgpack::sbuffer buffer;
  write_observation_msgpack(observation, buffer);
  const std::string bytes(buffer.data(), buffer.size());
  const auto handle = msgpack::unpack(buffer.data(), buffer.size());
  const auto& time = handle.get().via.map.ptr[5];
  ASSERT_EQ(time.key.as<std::string>(), "time");
  EXPECT_EQ(time.val.type, msgpack::type::FLOAT64);
  EXPECT_DOUBLE_EQ(time.val.via.f64, 2.0);
  // float64 marker 0xcb followed by 2.0 big-endian.
  const std::string two("\xa4time\xcb\x40\x00\x00\x00\x00\x00\x00\x00", 14);
  EXPECT_NE(bytes.find(two), std::string::npos);
}

TEST(ObservationDict, NanStaysAFloatNotNil) {
  Observation observation = make_observation(false);
  observation.servo[kLeftWheel].position = std::nan("");
  msgpack::sbuffer buffer;
  write_observation_msgpack(observation, buffer);
  const auto handle = msgpack::unpack(buffer.data(), buffer.size());
  const auto tree = checked_to_json(handle.get(), "");  // fails on nil
  EXPECT_TRUE(tree["servo"]["left_wheel"]["position"].is_number_float());
}

TEST(ObservationDict, BufferIsReusedWithoutGrowing) {
  msgpack::sbuffer buffer;
  write_observation_msgpack(make_observation(true), buffer);
  const std::size_t size = buffer.size();
  const char* data = buffer.data();
  write_observation_msgpack(make_observation(true), buffer);
  EXPECT_EQ(buffer.size(), size);  // replaced, not appended
  EXPECT_EQ(buffer.data(), data);  // same storage
}

}  // namespace
}  // namespace upkie_rl
