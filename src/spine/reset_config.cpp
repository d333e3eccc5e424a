#include "spine/reset_config.hpp"

#include <cmath>
#include <string>
#include <string_view>
#include <utility>

#include "sim/msgpack_float64.hpp"
#include "spine/spine_error.hpp"

namespace upkie_rl {
namespace {

class ConfigPacker {
 public:
  explicit ConfigPacker(msgpack::sbuffer& buffer) : buffer_(buffer), packer_(buffer) {}
  void map(std::uint32_t size) { packer_.pack_map(size); }
  void key(std::string_view key) {
    packer_.pack_str(static_cast<std::uint32_t>(key.size()));
    packer_.pack_str_body(key.data(), static_cast<std::uint32_t>(key.size()));
  }
  void real(std::string_view name, double value) {
    key(name);
    pack_float64(buffer_, value);
  }
  void reals(std::string_view name, const double* values, std::uint32_t size) {
    key(name);
    packer_.pack_array(size);
    for (std::uint32_t i = 0; i < size; ++i) pack_float64(buffer_, values[i]);
  }

 private:
  msgpack::sbuffer& buffer_;
  msgpack::packer<msgpack::sbuffer> packer_;
};

// Keys both the writer and the readers of the Start configuration use.
constexpr std::string_view kBullet = "bullet";
constexpr std::string_view kReset = "reset";
constexpr std::string_view kTorqueControl = "torque_control";
constexpr std::string_view kOrientation = "orientation_base_in_world";

/// bullet.reset.* (the public Bullet spine's reset state), each key once for the writer and
/// the reader, in key order: `visit(key, numbers, size)`; the orientation is [w, x, y, z]
/// in `wxyz`, which the caller fills (writer) or converts (reader).
template <typename State, typename Visitor>
void visit_reset_fields(State& state, double* wxyz, Visitor&& visit) {
  visit("angular_velocity_base_in_base", state.angular_velocity_base_in_base.data(), 3);
  visit("joint_configuration", state.joint_configuration.data(), kNumServos);
  visit("linear_velocity_base_to_world_in_world",
        state.linear_velocity_base_to_world_in_world.data(), 3);
  visit(kOrientation, wxyz, 4);
  visit("position_base_in_world", state.position_base_in_world.data(), 3);
}

/// bullet.torque_control.*, in key order: `visit(key, gain)`.
template <typename Gains, typename Visitor>
void visit_torque_control_fields(Gains& gains, Visitor&& visit) {
  visit("kd", gains.kd);
  visit("kp", gains.kp);
}

/// Reads an array of `size` finite numbers at key `key` of the map at `prefix`.
void read_array(const Dictionary& map, std::string_view key, double* out, std::size_t size,
                std::string_view prefix = "bullet.reset.") {
  if (!map.has(key)) return;
  const std::string path = std::string(prefix) + std::string(key);
  const Dictionary& value = map.at(key);
  if (value.is_map() || value.kind() == Dictionary::Kind::kBool ||
      value.kind() == Dictionary::Kind::kInt || value.kind() == Dictionary::Kind::kFloat ||
      value.kind() == Dictionary::Kind::kString || value.as_array().size() != size) {
    throw SpineError("spine configuration '" + path + "' must be an array of " +
                     std::to_string(size) + " numbers");
  }
  const auto& array = value.as_array();
  for (std::size_t i = 0; i < size; ++i) {
    if (!std::isfinite(array[i])) {
      throw SpineError("spine configuration '" + path + "' has a non-finite element");
    }
    out[i] = array[i];
  }
}

/// Reads the finite non-negative number at key `key` of the map at `prefix` into `out`
/// (unchanged when the key is absent).
void read_non_negative(const Dictionary& map, std::string_view key, double& out,
                       std::string_view prefix) {
  if (!map.has(key)) return;
  const Dictionary& value = map.at(key);
  const bool is_number =
      value.kind() == Dictionary::Kind::kInt || value.kind() == Dictionary::Kind::kFloat;
  if (!is_number || !std::isfinite(value.as_number()) || value.as_number() < 0.0) {
    throw SpineError("spine configuration '" + std::string(prefix) + std::string(key) +
                     "' must be a finite non-negative number");
  }
  out = value.as_number();
}

}  // namespace

void write_start_config_msgpack(const ResetState& state, const SpineStartParameters& parameters,
                                msgpack::sbuffer& buffer) {
  buffer.clear();
  ConfigPacker packer(buffer);
  packer.map(5);

  packer.key("base_orientation");
  packer.map(1);
  double row_major[9];
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) row_major[3 * i + j] = parameters.rotation_base_to_imu(i, j);
  }
  packer.reals("rotation_base_to_imu", row_major, 9);

  packer.key(kBullet);
  packer.map(2);
  packer.key(kReset);
  packer.map(5);
  const Eigen::Quaterniond& q = state.orientation_base_in_world;
  double wxyz[4] = {q.w(), q.x(), q.y(), q.z()};
  visit_reset_fields(state, wxyz, [&](std::string_view key, const double* values, int size) {
    packer.reals(key, values, static_cast<std::uint32_t>(size));
  });
  packer.key(kTorqueControl);
  packer.map(2);
  visit_torque_control_fields(parameters,
                              [&](std::string_view key, double gain) { packer.real(key, gain); });

  packer.key("floor_contact");
  packer.map(1);
  packer.real("upper_leg_torque_threshold", 10.0);

  packer.key("wheel_contact");
  packer.map(5);
  packer.real("cutoff_period", 0.2);
  packer.real("liftoff_inertia", 0.001);
  packer.real("min_touchdown_acceleration", 2.0);
  packer.real("min_touchdown_torque", 0.015);
  packer.real("touchdown_inertia", 0.004);

  packer.key("wheel_odometry");
  packer.map(1);
  packer.key("signed_radius");
  packer.map(2);
  packer.real("left_wheel", +parameters.wheel_radius);
  packer.real("right_wheel", -parameters.wheel_radius);
}

ResetState reset_state_from_config(const Dictionary& config) {
  ResetState state;
  if (!config.has(kBullet) || !config.at(kBullet).has(kReset)) return state;
  const Dictionary& reset = config.at(kBullet).at(kReset);
  if (!reset.is_map()) throw SpineError("spine configuration 'bullet.reset' is not a map");
  double wxyz[4];
  visit_reset_fields(state, wxyz, [&](std::string_view key, double* values, int size) {
    read_array(reset, key, values, static_cast<std::size_t>(size));
  });
  if (reset.has(kOrientation)) {
    Eigen::Quaterniond q(wxyz[0], wxyz[1], wxyz[2], wxyz[3]);
    if (!(q.norm() > 1e-6)) {
      throw SpineError("spine configuration 'bullet.reset.orientation_base_in_world' is zero");
    }
    state.orientation_base_in_world = q.normalized();
  }
  return state;
}

ServoGains servo_gains_from_config(const Dictionary& config, const ServoGains& defaults) {
  ServoGains gains = defaults;
  if (!config.has(kBullet) || !config.at(kBullet).has(kTorqueControl)) return gains;
  const Dictionary& torque_control = config.at(kBullet).at(kTorqueControl);
  if (!torque_control.is_map()) {
    throw SpineError("spine configuration 'bullet.torque_control' is not a map");
  }
  visit_torque_control_fields(gains, [&](std::string_view key, double& gain) {
    read_non_negative(torque_control, key, gain, "bullet.torque_control.");
  });
  return gains;
}

ImuUncertainty imu_uncertainty_from_config(const Dictionary& config) {
  ImuUncertainty uncertainty;
  if (!config.has(kBullet) || !config.at(kBullet).has("imu_uncertainty")) return uncertainty;
  constexpr std::string_view kPrefix = "bullet.imu_uncertainty.";
  const Dictionary& imu = config.at(kBullet).at("imu_uncertainty");
  if (!imu.is_map()) throw SpineError("spine configuration 'bullet.imu_uncertainty' is not a map");
  read_array(imu, "accelerometer_bias", uncertainty.accelerometer_bias.data(), 3, kPrefix);
  read_array(imu, "gyroscope_bias", uncertainty.gyroscope_bias.data(), 3, kPrefix);
  read_non_negative(imu, "accelerometer_noise", uncertainty.accelerometer_noise, kPrefix);
  read_non_negative(imu, "gyroscope_noise", uncertainty.gyroscope_noise, kPrefix);
  return uncertainty;
}

}  // namespace upkie_rl
