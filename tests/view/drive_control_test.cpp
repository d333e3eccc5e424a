#include "view/drive_control.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "view/drive_message.hpp"
#include "view/drive_protocol.hpp"
#include "view/driver_arbiter.hpp"
#include "view/rate_limiter.hpp"
#include "view/view_error.hpp"

namespace upkie_rl {
namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

const DriveLimits kLimits{1.0, 1.5};

std::string command(std::uint64_t seq, double vx, double wz) {
  return nlohmann::json{{drive_keys::kType, drive_keys::kCommand},
                        {drive_keys::kSequence, seq},
                        {drive_keys::kForwardVelocity, vx},
                        {drive_keys::kYawRate, wz}}
      .dump();
}

nlohmann::json parsed(const std::string& text) { return nlohmann::json::parse(text); }

// Messages

TEST(DriveMessage, ParsesACommandWithinTheLimits) {
  const DriveMessage message = parse_drive_message(command(7, -1.0, 1.5), kLimits);
  EXPECT_EQ(message.kind, DriveMessage::Kind::kCommand);
  EXPECT_EQ(message.sequence, 7u);
  EXPECT_EQ(message.forward_velocity, -1.0);
  EXPECT_EQ(message.yaw_rate, 1.5);
}

TEST(DriveMessage, ParsesResetPauseAndPush) {
  EXPECT_EQ(parse_drive_message(R"({"type":"reset"})", kLimits).kind, DriveMessage::Kind::kReset);
  EXPECT_EQ(parse_drive_message(R"({"type":"pause"})", kLimits).kind, DriveMessage::Kind::kPause);
  const DriveMessage push = parse_drive_message(R"({"type":"push","heading":1.5})", kLimits);
  EXPECT_EQ(push.kind, DriveMessage::Kind::kPush);
  EXPECT_EQ(push.heading, 1.5);
}

/// The reason of the refusal of `text`, or "accepted".
std::string refusal_of(const std::string& text) {
  try {
    parse_drive_message(text, kLimits);
  } catch (const DriveMessageError& error) {
    return error.what();
  }
  return "accepted";
}

TEST(DriveMessage, RefusesMalformedMessagesNamingTheProblem) {
  EXPECT_EQ(refusal_of("{not json"), "the message is not JSON");
  EXPECT_EQ(refusal_of("[1, 2]"), "the message is not a JSON object");
  EXPECT_EQ(refusal_of(R"({"seq": 1})"), "the message has no \"type\" string");
  EXPECT_EQ(refusal_of(R"({"type": "fly"})"), "unknown message type \"fly\"");
  EXPECT_EQ(refusal_of(R"({"type":"command","seq":1,"yaw_rate":0})"),
            "no \"forward_velocity\" in the message");
  EXPECT_EQ(refusal_of(R"({"type":"command","seq":1,"forward_velocity":"1","yaw_rate":0})"),
            "\"forward_velocity\" is not a number");
  // JSON.stringify(NaN) is null.
  EXPECT_EQ(refusal_of(R"({"type":"command","seq":1,"forward_velocity":null,"yaw_rate":0})"),
            "\"forward_velocity\" is not a number");
  EXPECT_EQ(refusal_of(R"({"type":"command","seq":1.5,"forward_velocity":0,"yaw_rate":0})"),
            "\"seq\" is not a whole number >= 0");
  EXPECT_EQ(refusal_of(R"({"type":"command","seq":-1,"forward_velocity":0,"yaw_rate":0})"),
            "\"seq\" is not a whole number >= 0");
  EXPECT_EQ(refusal_of(R"({"type":"push"})"), "no \"heading\" in the message");
}

TEST(DriveMessage, RefusesValuesThatAreNotFiniteOrOutOfRange) {
  EXPECT_NE(refusal_of(R"({"type":"command","seq":1,"forward_velocity":1e999,"yaw_rate":0})"),
            "accepted");
  EXPECT_EQ(refusal_of(command(1, 1.01, 0.0)).rfind("\"forward_velocity\" 1.010000 is outside", 0),
            0u);
  EXPECT_EQ(refusal_of(command(1, 0.0, -1.6)).rfind("\"yaw_rate\" -1.600000 is outside", 0), 0u);
  EXPECT_EQ(refusal_of(command(1, 1.0, -1.5)), "accepted");
}

// Rate limiter

TEST(RateLimiter, AllowsABurstThenTheRate) {
  RateLimiter limiter(10.0, 3.0);
  const auto start = Clock::now();
  EXPECT_TRUE(limiter.allow(start));
  EXPECT_TRUE(limiter.allow(start));
  EXPECT_TRUE(limiter.allow(start));
  EXPECT_FALSE(limiter.allow(start));
  EXPECT_FALSE(limiter.allow(start + milliseconds(50)));  // half a token
  EXPECT_TRUE(limiter.allow(start + milliseconds(100)));
  EXPECT_FALSE(limiter.allow(start + milliseconds(100)));
  // Tokens accumulate up to the burst only.
  EXPECT_TRUE(limiter.allow(start + milliseconds(10'000)));
  EXPECT_TRUE(limiter.allow(start + milliseconds(10'000)));
  EXPECT_TRUE(limiter.allow(start + milliseconds(10'000)));
  EXPECT_FALSE(limiter.allow(start + milliseconds(10'000)));
}

TEST(RateLimiter, RefusesBadSettings) {
  EXPECT_THROW(RateLimiter(0.0, 1.0), ViewError);
  EXPECT_THROW(RateLimiter(10.0, 0.5), ViewError);
  EXPECT_THROW(RateLimiter(std::nan(""), 1.0), ViewError);
}

// Arbiter

TEST(DriverArbiter, OneDriverAtATimeUntilItReleases) {
  DriverArbiter arbiter;
  EXPECT_FALSE(arbiter.driver().has_value());
  EXPECT_TRUE(arbiter.claim(1));
  EXPECT_TRUE(arbiter.claim(1));
  EXPECT_FALSE(arbiter.claim(2));
  EXPECT_FALSE(arbiter.release(2));
  EXPECT_TRUE(arbiter.is_driver(1));
  EXPECT_TRUE(arbiter.release(1));
  EXPECT_FALSE(arbiter.driver().has_value());
  EXPECT_TRUE(arbiter.claim(2));
}

// Control

TEST(DriveControl, TheFirstPageToSendDrivesAndTheOthersAreRefused) {
  DriveControl control(kLimits);
  const auto now = Clock::now();
  EXPECT_EQ(parsed(control.status_message(1))[drive_keys::kRole], drive_keys::kFree);
  const DriveControl::Reply first = control.receive(1, command(1, 0.5, 0.0), now);
  EXPECT_TRUE(first.to_sender.empty());
  EXPECT_TRUE(first.status_changed);
  EXPECT_EQ(parsed(control.status_message(1))[drive_keys::kRole], drive_keys::kDriver);
  EXPECT_EQ(parsed(control.status_message(2))[drive_keys::kRole], drive_keys::kWatcher);
  const DriveControl::Reply second = control.receive(2, command(1, -0.5, 0.0), now);
  EXPECT_EQ(parsed(second.to_sender)[drive_keys::kType], drive_keys::kRefused);
  const DriveInputs inputs = control.take();
  EXPECT_TRUE(inputs.new_command);
  EXPECT_EQ(inputs.forward_velocity, 0.5);  // not the watcher's
  EXPECT_EQ(control.statistics().refused, 1u);
}

TEST(DriveControl, ABadMessageLeavesTheCommandAsItWas) {
  DriveControl control(kLimits);
  const auto now = Clock::now();
  control.receive(1, command(1, 0.3, 0.2), now);
  EXPECT_FALSE(control.receive(1, command(2, 3.0, 0.0), now).to_sender.empty());
  EXPECT_FALSE(control.receive(1, "{", now).to_sender.empty());
  const DriveInputs inputs = control.take();
  EXPECT_EQ(inputs.forward_velocity, 0.3);
  EXPECT_EQ(inputs.yaw_rate, 0.2);
  EXPECT_EQ(inputs.sequence, 1u);
}

TEST(DriveControl, TheDriverLeavingZeroesTheCommandAndFreesControl) {
  DriveControl control(kLimits);
  const auto now = Clock::now();
  control.receive(1, command(1, 0.8, -1.0), now);
  control.receive(1, R"({"type":"pause"})", now);
  EXPECT_TRUE(control.take().paused);
  EXPECT_FALSE(control.disconnect(2));  // a watcher leaving changes nothing
  EXPECT_TRUE(control.disconnect(1));
  const DriveInputs inputs = control.take();
  EXPECT_TRUE(inputs.new_command);
  EXPECT_EQ(inputs.forward_velocity, 0.0);
  EXPECT_EQ(inputs.yaw_rate, 0.0);
  EXPECT_FALSE(inputs.paused);
  EXPECT_EQ(parsed(control.status_message(2))[drive_keys::kRole], drive_keys::kFree);
  EXPECT_TRUE(control.receive(2, command(1, 0.1, 0.0), now).status_changed);  // 2 drives now
}

TEST(DriveControl, ResetAndPushAreTakenOnce) {
  DriveControl control(kLimits);
  const auto now = Clock::now();
  control.receive(1, R"({"type":"reset"})", now);
  control.receive(1, R"({"type":"push","heading":-1})", now);
  const DriveInputs first = control.take();
  EXPECT_TRUE(first.reset);
  ASSERT_TRUE(first.push_heading.has_value());
  EXPECT_EQ(*first.push_heading, -1.0);
  const DriveInputs second = control.take();
  EXPECT_FALSE(second.reset);
  EXPECT_FALSE(second.push_heading.has_value());
  EXPECT_FALSE(second.new_command);
}

TEST(DriveControl, QuickPushesAreEachTakenInOrderAndAFloodIsRefused) {
  DriveControl control(kLimits);
  const auto now = Clock::now();
  for (std::size_t i = 0; i < kMaxWaitingPushes; ++i) {
    const std::string push = R"({"type":"push","heading":)" + std::to_string(i) + "}";
    EXPECT_TRUE(control.receive(1, push, now).to_sender.empty()) << i;
  }
  const std::string refusal = control.receive(1, R"({"type":"push","heading":0.5})", now).to_sender;
  EXPECT_NE(refusal.find("pushes come faster"), std::string::npos) << refusal;
  for (std::size_t i = 0; i < kMaxWaitingPushes; ++i) {
    const DriveInputs inputs = control.take();
    ASSERT_TRUE(inputs.push_heading.has_value()) << i;
    EXPECT_EQ(*inputs.push_heading, static_cast<double>(i));
  }
  EXPECT_FALSE(control.take().push_heading.has_value());
  EXPECT_EQ(control.statistics().refused, 1U);
}

TEST(DriveControl, PushesWaitWhileThePauseLasts) {
  DriveControl control(kLimits);
  const auto now = Clock::now();
  control.receive(1, R"({"type":"pause"})", now);
  control.receive(1, R"({"type":"push","heading":0.5})", now);
  control.receive(1, R"({"type":"push","heading":-0.5})", now);
  EXPECT_FALSE(control.take().push_heading.has_value());
  EXPECT_FALSE(control.take().push_heading.has_value());
  control.receive(1, R"({"type":"pause"})", now);  // resume
  EXPECT_EQ(control.take().push_heading, 0.5);
  EXPECT_EQ(control.take().push_heading, -0.5);
  EXPECT_FALSE(control.take().push_heading.has_value());
}

TEST(DriveControl, FloodsAreCutByTheRateLimitAndToldOnce) {
  DriveControl control(kLimits, DriveRateSettings{10.0, 5.0});
  const auto now = Clock::now();
  int refusals = 0;
  for (int i = 1; i <= 100; ++i) {
    if (!control.receive(1, command(i, 0.01 * i, 0.0), now).to_sender.empty()) ++refusals;
  }
  EXPECT_EQ(control.statistics().commands, 5u);
  EXPECT_EQ(control.statistics().rate_limited, 95u);
  EXPECT_EQ(refusals, 1);
  EXPECT_EQ(control.take().forward_velocity, 0.05);  // the last one let through
  // Another page has its own budget.
  EXPECT_FALSE(
      control.receive(2, command(1, 0.0, 0.0), now).to_sender.empty());  // refused: watcher
  EXPECT_EQ(control.statistics().refused, 1u);
}

TEST(DriveControl, AcknowledgesAppliedCommandsToTheDriverAndMeasuresLatency) {
  DriveControl control(kLimits);
  int calls = 0;
  control.set_applied_listener([&calls] { ++calls; });
  const auto received = Clock::now();
  control.receive(4, command(9, 0.2, 0.0), received);
  const DriveInputs inputs = control.take();
  control.applied(inputs, received + milliseconds(12));
  EXPECT_EQ(calls, 1);
  const auto acknowledgement = control.take_acknowledgement();
  ASSERT_TRUE(acknowledgement.has_value());
  EXPECT_EQ(acknowledgement->first, 4u);
  EXPECT_EQ(parsed(acknowledgement->second)[drive_keys::kSequence], 9);
  EXPECT_FALSE(control.take_acknowledgement().has_value());
  EXPECT_NEAR(control.statistics().latency_max, 0.012, 1e-9);
  control.applied(control.take(), received + milliseconds(40));  // nothing new: no sample
  EXPECT_EQ(control.statistics().applied, 1u);
  EXPECT_EQ(calls, 1);
}

// The body-height command of a velocity task with one.

DriveLimits height_limits() {
  DriveLimits limits{1.0, 1.5};
  limits.height_command = true;
  limits.min_height = 0.53;
  limits.max_height = 0.557;
  return limits;
}

std::string height_command(std::uint64_t seq, const nlohmann::json& height) {
  nlohmann::json message = parsed(command(seq, 0.2, 0.0));
  message[drive_keys::kHeight] = height;
  return message.dump();
}

TEST(DriveMessage, HeightWithinTheRangeOrStandingWhenAbsent) {
  EXPECT_EQ(parse_drive_message(height_command(1, 0.54), height_limits()).height, 0.54);
  EXPECT_EQ(parse_drive_message(command(2, 0.2, 0.0), height_limits()).height, 0.557);
  const auto refusal = [](const std::string& text, const DriveLimits& limits) {
    try {
      parse_drive_message(text, limits);
    } catch (const DriveMessageError& error) {
      return std::string(error.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(
      refusal(height_command(3, 0.5), height_limits()).rfind("\"height\" 0.500000 is outside", 0),
      0u);
  EXPECT_EQ(refusal(height_command(4, "low"), height_limits()), "\"height\" is not a number");
  EXPECT_EQ(refusal(height_command(5, 0.54), kLimits),
            "\"height\" given, but the task has no height command");
}

TEST(DriveControl, TheHeightReachesTheLoopAndTheLimitsTellThePage) {
  DriveControl control(height_limits());
  EXPECT_EQ(control.take().height, 0.557);  // standing until a page asks
  control.receive(1, height_command(1, 0.535), Clock::now());
  EXPECT_EQ(control.take().height, 0.535);
  const nlohmann::json with = drive_protocol_json(height_limits());
  EXPECT_EQ(with["limits"]["min_height"], 0.53);
  EXPECT_EQ(with["limits"]["max_height"], 0.557);
  EXPECT_EQ(with["keys"]["height"], drive_keys::kHeight);
  EXPECT_FALSE(drive_protocol_json(kLimits)["limits"].contains("min_height"));
}

TEST(DriveControl, RefusesLimitsThatAreNotPositive) {
  EXPECT_THROW(DriveControl(DriveLimits{0.0, 1.0}), ViewError);
  EXPECT_THROW(DriveControl(DriveLimits{1.0, std::nan("")}), ViewError);
  DriveLimits empty_heights = height_limits();
  empty_heights.min_height = 0.6;
  EXPECT_THROW(DriveControl{empty_heights}, ViewError);
}

}  // namespace
}  // namespace upkie_rl
