// upkie-rl identify's fit: known physics recovered from logs the test writes, refusals, and
// the same result for the same log and seed.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <iostream>
#include <string>
#include <utility>

#include "common/temp_files.hpp"
#include "envs/records/robot_log.hpp"
#include "identify/excitation_log.hpp"
#include "identify/identification.hpp"

namespace upkie_rl {
namespace {

/// A log of `duration` seconds of `env_id` with `options` as the hidden physics.
RobotLog simulated_log(const std::string& name, const EnvOptions& options,
                       const std::string& env_id = "Upkie-Bullet-Servos", std::uint64_t seed = 0,
                       double duration = 3.0) {
  const auto path = testing::temp_path(name);
  ExcitationSettings excitation;
  excitation.duration = duration;
  excitation.seed = seed;
  write_excitation_log(env_id, options, excitation, path);
  return read_robot_log(path);
}

IdentificationResult fit(const RobotLog& log, const std::vector<std::string>& params,
                         const std::string& env_id = "Upkie-Bullet-Servos") {
  IdentificationSettings settings;
  settings.env_id = env_id;
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

/// The fit of `option` alone over `range` ("LOW:HIGH") on a 10 s MuJoCo log whose hidden
/// physics set it to `hidden`, with the excitation of `seed`.
IdentificationResult fit_one_hidden_on_mujoco(const std::string& option, const std::string& hidden,
                                              const std::string& range, std::uint64_t seed = 0) {
  constexpr const char* kMujoco = "Upkie-MuJoCo-Servos";
  const RobotLog log = simulated_log(option + ".mpack", {{option, hidden}}, kMujoco, seed, 10.0);
  return fit(log, {option + "=" + range}, kMujoco);
}

TEST(Identification, RecoversMassScaleAndDelayOnBullet) {
  const RobotLog log =
      simulated_log("mass_delay.mpack", {{"mass_scale", "1.3"}, {"action_delay", "2"}});
  const IdentificationResult result = fit(log, {"mass_scale=0.7:1.6", "action_delay=0:4"});
  EXPECT_NEAR(parameter(result, "mass_scale").value, 1.3, 0.05);
  EXPECT_EQ(parameter(result, "action_delay").value, 2.0);
  EXPECT_LT(result.rmse_after, 0.5 * result.rmse_before);
}

// The floor's friction shows only where a tire slips: 10 s of log (MuJoCo, 7 times faster
// to replay than Bullet). On 3 s logs of Bullet the fits were 1-20 % off.
TEST(Identification, RecoversFloorFrictionOnMuJoCo) {
  const IdentificationResult result = fit_one_hidden_on_mujoco("floor_friction", "0.6", "0.1:1.5");
  EXPECT_NEAR(parameter(result, "floor_friction").value, 0.6, 0.06);
  EXPECT_LT(result.rmse_after, result.rmse_before);
}

TEST(Identification, RecoversMassScaleOnMuJoCoForSeveralSeeds) {
  for (const std::uint64_t seed : {1, 2}) {
    const RobotLog log =
        simulated_log("mujoco_mass.mpack", {{"mass_scale", "1.3"}}, "Upkie-MuJoCo-Servos", seed);
    const IdentificationResult result = fit(log, {"mass_scale=0.7:1.6"}, "Upkie-MuJoCo-Servos");
    EXPECT_NEAR(parameter(result, "mass_scale").value, 1.3, 0.065) << "seed " << seed;
    EXPECT_LT(result.rmse_after, result.rmse_before) << "seed " << seed;
  }
}

TEST(Identification, RecoversGyroscopeBiasOnBullet) {
  const RobotLog log = simulated_log("gyroscope.mpack", {{"imu_gyroscope_bias_fixed_y", "0.03"}});
  const IdentificationResult result = fit(log, {"imu_gyroscope_bias_fixed_y=-0.1:0.1"});
  const FittedParameter& bias = parameter(result, "imu_gyroscope_bias_fixed_y");
  EXPECT_NEAR(bias.value, 0.03, 0.005);
  // Measured, not fitted: its standard error is that of its 0.2 s block means. (The replays
  // judge a bias poorly: on Bullet they predict 1-4 % worse with it than without.)
  EXPECT_GT(bias.uncertainty, 0.0);
  EXPECT_LT(bias.uncertainty, 0.005);
}

// The wheels' velocity loop shows in the kicks of the excitation: 10 s of log (on 3 s of
// Bullet the fit barely moved from the nominal gains).
TEST(Identification, RecoversWheelGainScaleOnMuJoCo) {
  const IdentificationResult result =
      fit_one_hidden_on_mujoco("wheel_servo_gain_scale", "1.5", "0.5:3");
  EXPECT_NEAR(parameter(result, "wheel_servo_gain_scale").value, 1.5, 0.075);
  EXPECT_LT(result.rmse_after, result.rmse_before);
}

// The legs are held, and how far they give under the body's weight shows the leg servos'
// stiffness: measured +0.4 % on seeds 1 and 2.
TEST(Identification, RecoversLegGainScaleOnMuJoCo) {
  const IdentificationResult result =
      fit_one_hidden_on_mujoco("leg_servo_gain_scale", "0.7", "0.3:3", 1);
  EXPECT_NEAR(parameter(result, "leg_servo_gain_scale").value, 0.7, 0.035);
  EXPECT_LT(result.rmse_after, 0.5 * result.rmse_before);
}

// The delay-lag ridge at 5 ms steps: on this 60 s MuJoCo log (seed 4 of identify_goals, the
// goals' five parameters) the fit ends one step short, 1 step and 38 ms for the hidden 2
// and 30, predicting better than 2 steps would. What the fit owes the user is an
// uncertainty that says so: a delay reported +-0 must be the hidden one.
TEST(Identification, TheDelaysUncertaintyCoversTheHiddenDelay) {
  const RobotLog log = simulated_log("ridge.mpack",
                                     {{"mass_scale", "1.2"},
                                      {"payload_mass", "1"},
                                      {"payload_offset_x", "0.04"},
                                      {"floor_friction", "0.6"},
                                      {"action_delay", "2"},
                                      {"action_lag_min", "0.03"},
                                      {"action_lag_max", "0.03"}},
                                     "Upkie-MuJoCo-Servos", 4, 60.0);
  IdentificationSettings settings;
  settings.env_id = "Upkie-MuJoCo-Servos";
  settings.options = {{"payload_mass", "1"}};
  settings.parameters =
      parse_parameter_requests({"mass_scale=0.6:1.6", "payload_offset_x=-0.1:0.1",
                                "floor_friction=0.1:1.5", "action_delay=0:4", "action_lag=0:0.1"});
  const IdentificationResult result = identify(log, settings);
  std::cout << identification_json(result) << std::endl;
  const FittedParameter& delay = parameter(result, "action_delay");
  EXPECT_LE(std::abs(delay.value - 2.0), delay.uncertainty) << delay.value;
  EXPECT_NEAR(parameter(result, "mass_scale").value, 1.2, 0.06);
  EXPECT_NEAR(parameter(result, "floor_friction").value, 0.6, 0.03);
  // The values the log cannot tell from the fit hold the hidden ones (measured: mass
  // 1.175-1.234, payload 0.0381-0.0412 m, friction 0.519-0.645). Not the lag's: it is
  // conditional on the delay, one step short here, and the delay's +-1 says so.
  for (const auto& [name, hidden] : {std::pair<std::string, double>{"mass_scale", 1.2},
                                     {"payload_offset_x", 0.04},
                                     {"floor_friction", 0.6}}) {
    const FittedParameter& fitted = parameter(result, name);
    EXPECT_LE(fitted.low, hidden) << name;
    EXPECT_GE(fitted.high, hidden) << name;
    EXPECT_LT(fitted.high - fitted.low, 0.25 * hidden) << name;
  }
}

// Bullet's floor friction, fitted alone on 60 s of log with the rest of the physics known:
// frictions from well below the hidden one to a little above it predict this log alike (the
// tires rarely near slipping), and the fit stops 11 % high (0.667 for 0.6) with a
// curvature's uncertainty of +-0.002. The interval must say what the
// log cannot tell apart (measured 0.463-0.687), and still bound the friction: a fit whose
// interval spans the range informs nothing.
TEST(Identification, TheFrictionsIntervalHoldsWhatTheLogCannotTellApart) {
  const EnvOptions known = {{"mass_scale", "1.2"},        {"payload_mass", "1"},
                            {"payload_offset_x", "0.04"}, {"action_delay", "2"},
                            {"action_lag_min", "0.03"},   {"action_lag_max", "0.03"}};
  EnvOptions hidden = known;
  hidden.emplace_back("floor_friction", "0.6");
  const RobotLog log = simulated_log("flat_friction.mpack", hidden, "Upkie-Bullet-Servos", 1, 60.0);
  IdentificationSettings settings;
  settings.options = known;
  settings.parameters = parse_parameter_requests({"floor_friction=0.1:1.5"});
  const IdentificationResult result = identify(log, settings);
  std::cout << identification_json(result) << std::endl;
  const FittedParameter& friction = parameter(result, "floor_friction");
  EXPECT_LE(friction.low, 0.6);
  EXPECT_GE(friction.high, 0.6);
  EXPECT_LE(friction.low, friction.value);
  EXPECT_GE(friction.high, friction.value);
  EXPECT_GT(friction.low, 0.1);
  EXPECT_LT(friction.high, 1.0);
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
  EXPECT_NE(refusal("joint_friction").find("fit joint_friction_fixed"), std::string::npos);
  EXPECT_NE(refusal("wheel_servo_gain_scale=0.1:2").find("leaves the declared range"),
            std::string::npos);
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

// A log is replayed with one delay, in the environment's steps: a delay drawn per episode
// or given in seconds is refused.
TEST(Identification, DelayDrawnPerEpisodeIsRefusedNamingTheOption) {
  const RobotLog log = simulated_log("delay_max.mpack", {});
  IdentificationSettings settings;
  settings.env_id = "Upkie-Bullet-Servos";
  settings.parameters = parse_parameter_requests({"mass_scale"});
  for (const auto& [option, value] :
       {std::pair{"action_delay_max", "2"}, {"action_delay_time", "0.01"}}) {
    settings.options = {{option, value}};
    try {
      identify(log, settings);
      FAIL() << option << " passed";
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find(option), std::string::npos);
    }
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

/// `log` with the robot lying on its back from `fall_time` on (base pitched by -pi/2).
RobotLog fallen_from(RobotLog log, double fall_time) {
  const Eigen::Matrix3d lying =
      Eigen::AngleAxisd(-M_PI / 2.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
  for (LoggedCycle& cycle : log.cycles) {
    if (cycle.time - log.cycles.front().time < fall_time) continue;
    cycle.observation.base_orientation.rotation_base_to_world = lying;
    cycle.observation.base_orientation.pitch = -M_PI / 2.0;
  }
  return log;
}

// A robot's log may end in a fall: replays of the lying robot are left out, counted, and
// the fit is that of the standing part.
TEST(Identification, ReplaysWhereTheRobotIsDownAreLeftOut) {
  const RobotLog log = simulated_log("down.mpack", {{"mass_scale", "1.3"}}, "Upkie-MuJoCo-Servos");
  const IdentificationResult standing = fit(log, {"mass_scale=0.7:1.6"}, "Upkie-MuJoCo-Servos");
  EXPECT_EQ(standing.windows_down, 0u);
  const IdentificationResult fallen =
      fit(fallen_from(log, 2.0), {"mass_scale=0.7:1.6"}, "Upkie-MuJoCo-Servos");
  EXPECT_GT(fallen.windows_down, 0u);
  EXPECT_EQ(fallen.windows + fallen.windows_down, standing.windows);
  EXPECT_NEAR(parameter(fallen, "mass_scale").value, 1.3, 0.065);
  EXPECT_NE(
      identification_json(fallen).find("\"windows_down\":" + std::to_string(fallen.windows_down)),
      std::string::npos);
  try {
    fit(fallen_from(log, 0.0), {"mass_scale"}, "Upkie-MuJoCo-Servos");
    FAIL() << "a log of a lying robot";
  } catch (const RobotLogError& error) {
    EXPECT_NE(std::string(error.what()).find("down"), std::string::npos) << error.what();
  }
}

// The tests' logs are of a standing robot: a hidden physics the excitation topples is
// refused, naming the time of the fall, rather than written as a log of a lying robot.
TEST(ExcitationLog, RefusesToLogAFall) {
  const auto path = testing::temp_path("fall.mpack");
  ExcitationSettings excitation;
  excitation.duration = 10.0;
  try {
    write_excitation_log("Upkie-MuJoCo-Servos", {{"torque_limit_scale", "0.2"}}, excitation, path);
    FAIL() << "the robot cannot balance with a fifth of its torque";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("fell at"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace upkie_rl

// The YAML for training holds what the log told, nothing the solver made up: a parameter
// not identifiable from the log is named in a comment, not written over the configuration.
TEST(IdentificationYaml, LeavesOutWhatTheLogDidNotInform) {
  upkie_rl::IdentificationResult result;
  result.parameters.push_back({"floor_friction", "", 0.5, 0.01, true, ""});
  result.parameters.push_back(
      {"action_lag", "s", 0.0003, 0.0, false, "the log does not excite it"});
  const std::string yaml =
      upkie_rl::identification_yaml(result, "robot.mpack", "Upkie-MuJoCo-Servos");
  EXPECT_NE(yaml.find("\n    floor_friction: 0.5\n"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("--set env.options.floor_friction=0.5"), std::string::npos) << yaml;
  EXPECT_EQ(yaml.find("action_lag_m"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("# left out, not identifiable from this log: action_lag (the log does "
                      "not excite it)"),
            std::string::npos)
      << yaml;

  result.parameters.erase(result.parameters.begin());
  const std::string nothing =
      upkie_rl::identification_yaml(result, "robot.mpack", "Upkie-MuJoCo-Servos");
  EXPECT_NE(nothing.find("env:\n  options: {}\n"), std::string::npos) << nothing;
}

// A delay uncertain by a step comes with what the log pins down: the delay and the lag's sum.
TEST(IdentificationText, NamesTheLatencyWhenTheDelayIsUncertain) {
  upkie_rl::IdentificationResult result;
  result.timestep = 0.005;
  result.parameters.push_back({"action_delay", "steps", 1.0, 1.0, true, ""});
  result.parameters.push_back({"action_lag", "s", 0.0377, 0.0002, true, ""});
  EXPECT_EQ(upkie_rl::actuation_latency_line(result),
            "action_delay and action_lag trade against each other on this log: their sum, 1 x "
            "5 ms + 37.7 ms = 42.7 ms, is what it pins down");
  result.parameters[0].uncertainty = 0.0;  // the delay told apart from its neighbours
  EXPECT_EQ(upkie_rl::actuation_latency_line(result), "");
  result.parameters[0].uncertainty = 1.0;
  result.parameters.pop_back();  // no lag fitted
  EXPECT_EQ(upkie_rl::actuation_latency_line(result), "");
}
