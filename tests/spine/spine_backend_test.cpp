#include "spine/spine_backend.hpp"

#include <fcntl.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cmath>
#include <functional>
#include <optional>
#include <thread>

#include "fake_simulation.hpp"
#include "message_builder.hpp"
#include "spine/spine_error.hpp"
#include "spine/spine_server.hpp"

namespace upkie_rl {
namespace {

using testing::FakeSimulation;

/// Our agent against our spine (fake simulation), the spine running in its own thread.
class SpineBackendTest : public ::testing::Test {
 protected:
  void start_spine(bool real_time, double timestep = 0.005) {
    simulation_ = std::make_unique<FakeSimulation>(timestep);
    server_config_.shm_name = testing::unique_shm_name("backend");
    server_config_.real_time = real_time;
    server_ = std::make_unique<SpineServer>(*simulation_, server_config_);
    thread_ = std::thread([this] { server_->run(interrupt_); });
  }

  SpineBackendConfig backend_config(bool regulate) const {
    SpineBackendConfig config;
    config.shm_name = server_config_.shm_name;
    config.regulate_frequency = regulate;
    config.open_tries = 1;
    return config;
  }

  /// Stops the spine thread; its simulation may then be inspected from the test thread.
  /// (The agent and the spine map the shared memory at different addresses, so a race
  /// detector cannot see the request word that orders their accesses.)
  void stop_spine() {
    interrupt_ = true;
    if (thread_.joinable()) thread_.join();
  }

  void TearDown() override { stop_spine(); }

  std::unique_ptr<FakeSimulation> simulation_;
  SpineServerConfig server_config_;
  std::unique_ptr<SpineServer> server_;
  std::atomic<bool> interrupt_{false};
  std::thread thread_;
};

TEST_F(SpineBackendTest, ResetAndStepOnRequest) {
  start_spine(false);
  {
    SpineBackend backend(backend_config(false));
    EXPECT_DOUBLE_EQ(backend.agent_timestep(), 0.005);
    ResetState state;
    state.joint_configuration = {0.0, 0.5, 0.0, 0.0, -0.5, 0.0};
    state.position_base_in_world = {0.0, 0.0, 0.7};
    const Observation& first = backend.reset(state);
    EXPECT_DOUBLE_EQ(first.time, 0.0);
    EXPECT_DOUBLE_EQ(first.servo[kLeftKnee].position, 0.5);
    EXPECT_DOUBLE_EQ(first.sim_base.position.z(), 0.7);

    ServoAction action;
    for (ServoCommand& command : action) command.maximum_torque = 1.0;
    action[kLeftWheel].velocity = 10.0;
    for (int i = 1; i <= 20; ++i) {
      const Observation& observation = backend.step(action);
      EXPECT_NEAR(observation.time, 0.005 * i, 1e-12);
    }
    EXPECT_NEAR(backend.observation().servo[kLeftWheel].position, 20 * 0.005 * 10.0, 1e-9);

    const Observation& again = backend.reset(ResetState{});
    EXPECT_DOUBLE_EQ(again.time, 0.0);
  }
  // The backend's destructor asked for a stop.
  for (int i = 0; i < 1000 && server_->state() != SpineState::kSendStops; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  EXPECT_EQ(server_->state(), SpineState::kSendStops);
  stop_spine();
  EXPECT_EQ(simulation_->actions.size(), 20u);
  EXPECT_EQ(simulation_->resets.size(), 2u);
}

TEST_F(SpineBackendTest, RealTimeSpineWithRegulatedAgent) {
  start_spine(true, 0.001);
  SpineBackend backend(backend_config(true));
  backend.reset(ResetState{});
  double previous_time = backend.observation().time;
  ServoAction action;
  for (ServoCommand& command : action) command.maximum_torque = 1.0;
  for (int i = 0; i < 20; ++i) {
    const double time = backend.step(action).time;
    EXPECT_GT(time, previous_time);  // the spine kept simulating in between
    previous_time = time;
  }
  // 20 regulated steps at 200 Hz last ~0.1 s, during which the spine cycled on its own.
  EXPECT_GT(server_->nb_simulation_steps(), 20u);
}

/// Mean age [s] of the observation each action was computed from when the spine applied
/// it: a regulated agent at 50 Hz on a real-time spine of 1 ms cycles, each action computed
/// at once from the observation step() returned and marked by its wheel velocity.
double mean_observation_age_at_action(SpineBackend& backend, const FakeSimulation& simulation,
                                      const std::function<void()>& stop_spine) {
  constexpr int kSteps = 10;
  backend.reset(ResetState{});
  std::vector<double> observation_times = {backend.observation().time};
  ServoAction action;
  for (ServoCommand& command : action) command.maximum_torque = 1.0;
  for (int i = 1; i <= kSteps; ++i) {
    action[kLeftWheel].velocity = i;
    observation_times.push_back(backend.step(action).time);
  }
  stop_spine();
  double total_age = 0.0;
  for (int i = 1; i <= kSteps; ++i) {
    const auto& actions = simulation.actions;
    std::size_t k = 0;
    while (k < actions.size() && actions[k][kLeftWheel].velocity != i) ++k;
    EXPECT_LT(k, actions.size()) << "action " << i << " never applied";
    if (k == actions.size()) return 0.0;
    total_age += simulation.action_times[k] - observation_times[i - 1];
  }
  return total_age / kSteps;
}

TEST_F(SpineBackendTest, RegulatedAgentActsOnTheObservationOfTheTick) {
  start_spine(true, 0.001);
  SpineBackendConfig config = backend_config(true);
  config.agent_frequency = 50.0;
  SpineBackend backend(config);
  // Measured 0.9 ms: the action leaves within a cycle of the tick's observation. Returning
  // the action's own reply instead (below) measured 17 ms: 19 ms on every step but the
  // first, which leaves at once after the reset.
  EXPECT_LT(mean_observation_age_at_action(backend, *simulation_, [this] { stop_spine(); }), 0.006);
}

TEST_F(SpineBackendTest, WithoutFreshObservationsActionsApplyAPeriodLate) {
  start_spine(true, 0.001);
  SpineBackendConfig config = backend_config(true);
  config.agent_frequency = 50.0;
  config.fresh_observation = false;
  SpineBackend backend(config);
  EXPECT_GT(mean_observation_age_at_action(backend, *simulation_, [this] { stop_spine(); }), 0.012);
}

// On a spine that steps once per request, the requests a paced agent sends can be counted:
// a step on time sends its action twice (the second reply is the tick's observation), a
// step already late at its tick once (its own reply is as fresh, and a second spine cycle
// would only make the loop later).
TEST_F(SpineBackendTest, LateLoopSkipsTheRepeatedRequest) {
  start_spine(false);
  SpineBackendConfig config = backend_config(true);  // paced at 200 Hz
  SpineBackend backend(config);
  backend.reset(ResetState{});
  ServoAction action;
  for (ServoCommand& command : action) command.maximum_torque = 1.0;
  constexpr int kSteps = 10;
  for (int i = 0; i < kSteps; ++i) {
    backend.step(action);
    std::this_thread::sleep_for(std::chrono::milliseconds(8));  // longer than the 5 ms period
  }
  stop_spine();
  // The first step is on time (its tick is a period after it left), the nine others late.
  EXPECT_EQ(simulation_->actions.size(), 2u + (kSteps - 1));
}

TEST_F(SpineBackendTest, ActionBeforeStartIsAnInvalidRequest) {
  start_spine(false);
  SpineBackend backend(backend_config(false));
  ServoAction action;
  for (ServoCommand& command : action) command.maximum_torque = 1.0;
  try {
    backend.step(action);
    FAIL();
  } catch (const SpineError& error) {
    EXPECT_STREQ(error.what(), "invalid request, is the spine started?");
  }
  backend.reset(ResetState{});  // recovers
  EXPECT_NO_THROW(backend.step(action));
}

TEST_F(SpineBackendTest, NonFiniteCommandsAreRefusedBeforeSending) {
  start_spine(false);
  SpineBackend backend(backend_config(false));
  backend.reset(ResetState{});
  ServoAction action;
  for (ServoCommand& command : action) command.maximum_torque = 1.0;
  action[kRightHip].velocity = std::nan("");
  EXPECT_THROW(backend.step(action), InvalidCommandError);
  action[kRightHip].velocity = 0.0;
  action[kRightHip].position = std::nan("");  // NaN position is "no position loop"
  EXPECT_NO_THROW(backend.step(action));
  stop_spine();
  EXPECT_EQ(simulation_->actions.size(), 1u);
}

/// A robot-like observation: no `time`, no `sim`, integer fault/mode, extra keys; with
/// `imu_acceleration`, an `imu` map holding only `linear_acceleration` (0, 0, that).
std::string robot_observation(double wheel_velocity,
                              std::optional<double> imu_acceleration = std::nullopt) {
  testing::MessageBuilder message;
  message.map(imu_acceleration ? 5 : 4);
  message.key("base_orientation").map(2);
  message.key("angular_velocity").array(3).real(0.0).real(0.2).real(0.0);
  message.key("pitch").real(0.1);
  message.key("joystick").map(1).key("cross_button").boolean(false);
  message.key("servo").map(kNumServos);
  for (std::size_t i = 0; i < kNumServos; ++i) {
    message.key(kServoNames[i]).map(5);
    message.key("fault").integer(0).key("mode").integer(10);
    message.key("position").real(0.0).key("torque").real32(0.5f);
    message.key("velocity").real(is_wheel(i) ? wheel_velocity : 0.0);
  }
  message.key("wheel_odometry").map(2).key("position").real(0.0).key("velocity").real(0.3);
  if (imu_acceleration) {
    message.key("imu").map(1).key("linear_acceleration").array(3);
    message.real(0.0).real(0.0).real(*imu_acceleration);
  }
  return message.bytes();
}

/// A spine thread on fresh shared memory that answers every request at once: Start and
/// Action with `reply(number of actions so far)`, Stop by clearing.
class RobotLikeSpine {
 public:
  explicit RobotLikeSpine(std::function<std::string(int)> reply)
      : name_(testing::unique_shm_name("robot")),
        memory_(SharedMemory::create(name_)),
        thread_([this, reply = std::move(reply)] { serve(reply); }) {}
  ~RobotLikeSpine() {
    done_ = true;
    thread_.join();
  }
  RobotLikeSpine(const RobotLikeSpine&) = delete;
  RobotLikeSpine& operator=(const RobotLikeSpine&) = delete;

  /// A backend's configuration for this spine: on request, 100 Hz, one try.
  SpineBackendConfig backend_config() const {
    SpineBackendConfig config;
    config.shm_name = name_;
    config.regulate_frequency = false;
    config.agent_frequency = 100.0;
    config.open_tries = 1;
    return config;
  }

 private:
  void serve(const std::function<std::string(int)>& reply) {
    int actions = 0;
    while (!done_) {
      const std::uint32_t request = memory_.request();
      if (request == static_cast<std::uint32_t>(Request::kStart) ||
          request == static_cast<std::uint32_t>(Request::kAction)) {
        if (request == static_cast<std::uint32_t>(Request::kAction)) ++actions;
        const std::string bytes = reply(actions);
        memory_.write_payload({bytes.data(), bytes.size()});
        memory_.set_request(Request::kNone);
      } else if (request == static_cast<std::uint32_t>(Request::kStop)) {
        memory_.set_request(Request::kNone);
      }
      std::this_thread::yield();
    }
  }

  std::string name_;
  SharedMemory memory_;
  std::atomic<bool> done_{false};
  std::thread thread_;
};

TEST(SpineBackend, ReadsARobotSpineWithoutTimeOrGroundTruth) {
  RobotLikeSpine spine([](int actions) { return robot_observation(actions); });
  SpineBackend backend(spine.backend_config());
  const Observation& first = backend.reset(ResetState{});
  EXPECT_DOUBLE_EQ(first.time, 0.0);
  EXPECT_FALSE(first.has_sim);
  EXPECT_DOUBLE_EQ(first.base_orientation.pitch, 0.1);
  EXPECT_DOUBLE_EQ(first.servo[kLeftKnee].torque, 0.5);  // float32 accepted
  ServoAction action;
  for (ServoCommand& command : action) command.maximum_torque = 1.0;
  for (int i = 1; i <= 3; ++i) {
    const Observation& observation = backend.step(action);
    EXPECT_NEAR(observation.time, 0.01 * i, 1e-12);  // the agent's clock
    EXPECT_DOUBLE_EQ(observation.servo[kRightWheel].velocity, i);
  }
  EXPECT_DOUBLE_EQ(backend.reset(ResetState{}).time, 0.0);
}

// A policy that observes the IMU's acceleration must not run on the zeros an optional key
// the spine does not write would leave.
TEST(SpineBackend, RequiredImuAccelerationMissingIsRefusedNamingTheKey) {
  RobotLikeSpine spine([](int actions) { return robot_observation(actions); });
  SpineBackendConfig config = spine.backend_config();
  config.require_imu_acceleration = true;
  SpineBackend backend(config);
  try {
    backend.reset(ResetState{});
    FAIL() << "an observation without imu.linear_acceleration was accepted";
  } catch (const SpineError& error) {
    EXPECT_THAT(error.what(), ::testing::HasSubstr("'imu.linear_acceleration' is missing"));
    EXPECT_THAT(error.what(), ::testing::HasSubstr("observe_acceleration"));
  }
}

// Written on the first cycles, then dropped: the previous value is not kept.
TEST(SpineBackend, RequiredImuAccelerationIsReadAndItsLaterAbsenceRefused) {
  RobotLikeSpine spine([](int actions) {
    return actions < 2 ? robot_observation(actions, 9.5 + actions) : robot_observation(actions);
  });
  SpineBackendConfig config = spine.backend_config();
  config.require_imu_acceleration = true;
  SpineBackend backend(config);
  EXPECT_DOUBLE_EQ(backend.reset(ResetState{}).imu.linear_acceleration.z(), 9.5);
  ServoAction action;
  for (ServoCommand& command : action) command.maximum_torque = 1.0;
  EXPECT_DOUBLE_EQ(backend.step(action).imu.linear_acceleration.z(), 10.5);
  EXPECT_THROW(backend.step(action), SpineError);
}

TEST(SpineBackend, NoSpineFailsAfterTheConfiguredTries) {
  SpineBackendConfig config;
  config.shm_name = testing::unique_shm_name("absent");
  config.open_tries = 3;
  config.open_retry_delay = 0.01;
  try {
    SpineBackend backend(config);
    FAIL();
  } catch (const SpineError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("did not respond after 3 attempts"), std::string::npos) << message;
    EXPECT_NE(message.find(config.shm_name), std::string::npos);
  }
}

TEST(SpineBackend, StaleSharedMemoryTimesOutCleanly) {
  // A spine that died without unlinking: the object exists but nobody answers.
  const std::string name = testing::unique_shm_name("stale");
  const int fd = ::shm_open(name.c_str(), O_RDWR | O_CREAT, 0666);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::ftruncate(fd, 4096), 0);
  ::close(fd);
  {
    SpineBackendConfig config;
    config.shm_name = name;
    config.open_tries = 1;
    SpineBackend backend(config);
    try {
      backend.reset(ResetState{});
      FAIL();
    } catch (const SpineTimeoutError& error) {
      EXPECT_STREQ(error.what(), "spine did not process request within 100 ms, is it stopped?");
    }
  }  // the destructor's stop times out too, silently
  ::shm_unlink(name.c_str());
}

TEST(SpineBackend, TooSmallSharedMemoryIsRefused) {
  const std::string name = testing::unique_shm_name("small");
  const int fd = ::shm_open(name.c_str(), O_RDWR | O_CREAT, 0666);
  ASSERT_GE(fd, 0);
  ::close(fd);  // size 0
  SpineBackendConfig config;
  config.shm_name = name;
  config.open_tries = 1;
  EXPECT_THROW(SpineBackend backend(config), SpineError);
  ::shm_unlink(name.c_str());
}

}  // namespace
}  // namespace upkie_rl
