// upkie-rl identify's fit: known physics recovered from logs the test writes, refusals, and
// the same result for the same log and seed.

#include <gtest/gtest.h>

#include <iostream>
#include <string>

#include "common/temp_files.hpp"
#include "envs/robot_log.hpp"
#include "identify/excitation_log.hpp"
#include "identify/identification.hpp"

namespace upkie_rl {
namespace {

/// A 3 s log of Upkie-Bullet-Servos with `options` as the hidden physics.
RobotLog simulated_log(const std::string& name, const EnvOptions& options) {
  const auto path = testing::temp_path(name);
  ExcitationSettings excitation;
  excitation.duration = 3.0;
  write_excitation_log("Upkie-Bullet-Servos", options, excitation, path);
  return read_robot_log(path);
}

IdentificationResult fit(const RobotLog& log, const std::vector<std::string>& params) {
  IdentificationSettings settings;
  settings.env_id = "Upkie-Bullet-Servos";
  settings.parameters = parse_parameter_requests(params);
  settings.max_evaluations = 60;
  const IdentificationResult result = identify(log, settings);
  // The figures docs/identify.md reports.
  std::cout << identification_json(result) << std::endl;
  return result;
}

const FittedParameter& parameter(const IdentificationResult& result, const std::string& name) {
  for (const FittedParameter& fitted : result.parameters) {
    if (fitted.name == name) return fitted;
  }
  throw std::runtime_error("no parameter " + name);
}

TEST(Identification, RecoversMassScaleAndDelayOnBullet) {
  const RobotLog log =
      simulated_log("mass_delay.mpack", {{"mass_scale", "1.3"}, {"action_delay", "2"}});
  const IdentificationResult result = fit(log, {"mass_scale=0.7:1.6", "action_delay=0:4"});
  EXPECT_NEAR(parameter(result, "mass_scale").value, 1.3, 0.05);
  EXPECT_EQ(parameter(result, "action_delay").value, 2.0);
  EXPECT_LT(result.rmse_after, 0.5 * result.rmse_before);
}

TEST(Identification, RecoversFloorFrictionOnBullet) {
  const RobotLog log = simulated_log("friction.mpack", {{"floor_friction", "0.3"}});
  const IdentificationResult result = fit(log, {"floor_friction=0.1:1.5"});
  EXPECT_NEAR(parameter(result, "floor_friction").value, 0.3, 0.05);
  EXPECT_LT(result.rmse_after, result.rmse_before);
}

TEST(Identification, SameLogSameResult) {
  const RobotLog log = simulated_log("repeat.mpack", {{"mass_scale", "0.8"}});
  const IdentificationResult first = fit(log, {"mass_scale=0.6:1.2"});
  const IdentificationResult second = fit(log, {"mass_scale=0.6:1.2"});
  EXPECT_EQ(parameter(first, "mass_scale").value, parameter(second, "mass_scale").value);
  EXPECT_EQ(first.rmse_after, second.rmse_after);
}

TEST(Identification, ParameterOutsideItsRangeIsRefused) {
  const auto refusal = [](const std::string& text) -> std::string {
    try {
      parse_parameter_request(text);
    } catch (const std::invalid_argument& error) {
      return error.what();
    }
    return "";
  };
  EXPECT_NE(refusal("mass_scale=0.1:5").find("leaves the declared range"), std::string::npos);
  EXPECT_NE(refusal("mass_scale=2:1").find("LOW must be below HIGH"), std::string::npos);
  EXPECT_NE(refusal("wheel_size").find("unknown parameter"), std::string::npos);
  EXPECT_NE(refusal("joint_friction").find("cannot be fitted"), std::string::npos);
}

TEST(Identification, LogWithoutServoCommandsIsRefused) {
  const std::string header =
      "episode,step,t,pitch,ground_position,theta_dot,action.ground_velocity\n";
  std::string text = header;
  for (int i = 0; i < 200; ++i)
    text += "0," + std::to_string(i) + "," + std::to_string(0.005 * i) + ",0,0,0,0\n";
  const RobotLog log = read_record_log(text, "pendulum.csv");
  try {
    fit(log, {"mass_scale"});
    FAIL() << "a pendulum record has no servo commands";
  } catch (const RobotLogError& error) {
    EXPECT_NE(std::string(error.what()).find("no servo commands"), std::string::npos);
  }
}

TEST(Identification, WrongFrequencyIsRefused) {
  const auto path = testing::temp_path("frequency.mpack");
  ExcitationSettings excitation;
  excitation.duration = 1.0;
  write_excitation_log("Upkie-Bullet-Servos", {{"frequency", "300"}}, excitation, path);
  const RobotLog log = read_robot_log(path);
  try {
    fit(log, {"mass_scale"});
    FAIL() << "a 300 Hz log on a 200 Hz environment";
  } catch (const RobotLogError& error) {
    EXPECT_NE(std::string(error.what()).find("wrong frequency"), std::string::npos);
  }
}

}  // namespace
}  // namespace upkie_rl
