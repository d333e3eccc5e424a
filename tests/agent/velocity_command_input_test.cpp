// The velocity command inputs of upkie-rl-agent: lines of the standard input and keys,
// read through a pipe as the runner reads its standard input; the schedule of a file.

#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <string>

#include "agent/keyboard_command_input.hpp"
#include "agent/line_command_input.hpp"
#include "agent/scheduled_command_input.hpp"
#include "agent/velocity_commander.hpp"
#include "common/temp_files.hpp"

namespace upkie_rl {
namespace {

/// A pipe whose read end an input polls and whose write end the test types into.
class Pipe {
 public:
  Pipe() { EXPECT_EQ(::pipe(ends_.data()), 0); }
  ~Pipe() {
    for (int fd : ends_) {
      if (fd >= 0) ::close(fd);
    }
  }
  int read_end() const { return ends_[0]; }
  void write(const std::string& text) {
    ASSERT_EQ(::write(ends_[1], text.data(), text.size()), static_cast<ssize_t>(text.size()));
  }
  void close_write_end() {
    ::close(ends_[1]);
    ends_[1] = -1;
  }

 private:
  std::array<int, 2> ends_{-1, -1};
};

TEST(LineCommandInput, TakesTheLastCompleteLineAndNeverBlocks) {
  Pipe pipe;
  LineCommandInput input(pipe.read_end());
  EXPECT_FALSE(input.poll(0.0).has_value());  // nothing typed: returns at once
  pipe.write("0.2,0\n0.5, -0.25\n0.7");       // the last line is not finished
  const auto command = input.poll(0.0);
  ASSERT_TRUE(command.has_value());
  EXPECT_EQ(*command, (VelocityCommand{0.5, -0.25}));
  EXPECT_FALSE(input.poll(0.0).has_value());
  pipe.write(",1\n");
  EXPECT_EQ(input.poll(0.0), (VelocityCommand{0.7, 1.0}));
}

TEST(LineCommandInput, IgnoresCommentsMalformedAndOverlongLinesAndHoldsAtTheEnd) {
  Pipe pipe;
  LineCommandInput input(pipe.read_end());
  pipe.write("# comment\n\nfast please\n1,2,3,4\nnan,0\n0,0,nan\n" +
             std::string(LineCommandInput::kMaxLine + 10, '1') + "\n");
  EXPECT_FALSE(input.poll(0.0).has_value());
  pipe.write("-0.3,0.1\n");
  pipe.close_write_end();
  EXPECT_EQ(input.poll(0.0), (VelocityCommand{-0.3, 0.1}));
  EXPECT_FALSE(input.poll(0.0).has_value());  // end of input: the last command holds
}

TEST(LineCommandInput, AThirdNumberIsTheHeightWithoutItStanding) {
  Pipe pipe;
  LineCommandInput input(pipe.read_end());
  pipe.write("0.1,0,0.54\n");
  EXPECT_EQ(input.poll(0.0), (VelocityCommand{0.1, 0.0, 0.54}));
  pipe.write("0.2,0\n");
  EXPECT_EQ(input.poll(0.0), (VelocityCommand{0.2, 0.0, kStandingBaseHeight}));
}

TEST(KeyboardCommandInput, RAndFStepTheHeightWithinACrouchAndStanding) {
  Pipe pipe;
  KeyboardCommandInput input(pipe.read_end());
  pipe.write("r");  // already standing: the top
  EXPECT_EQ(input.poll(0.0), (VelocityCommand{0.0, 0.0, kStandingBaseHeight}));
  pipe.write("ff");
  EXPECT_NEAR(input.poll(0.0)->height, kStandingBaseHeight - 0.04, 1e-9);
  pipe.write("w ");  // a stop keeps the height
  EXPECT_NEAR(input.poll(0.0)->height, kStandingBaseHeight - 0.04, 1e-9);
  pipe.write(std::string(20, 'f'));
  EXPECT_EQ(input.poll(0.0)->height, kLowestHeightCommand);
}

TEST(VelocityCommander, ClampsTheHeightToTheTrainedRange) {
  VelocityCommandRanges trained;  // heights in [0.53, 0.557] m
  EXPECT_EQ(clamp_to_trained({0.0, 0.0, 0.40}, trained).height, 0.53);
  EXPECT_EQ(clamp_to_trained({0.0, 0.0, 0.545}, trained).height, 0.545);
  EXPECT_EQ(clamp_to_trained({2.0, 0.0, 0.545}, trained).forward_velocity, 1.0);
  trained.height_command = false;  // a policy without a height command stands
  EXPECT_EQ(clamp_to_trained({0.0, 0.0, 0.54}, trained).height, kStandingBaseHeight);
}

TEST(KeyboardCommandInput, LettersAndArrowsStepTheCommandSpaceStops) {
  Pipe pipe;
  KeyboardCommandInput input(pipe.read_end());
  EXPECT_FALSE(input.poll(0.0).has_value());
  pipe.write("www");
  EXPECT_EQ(input.poll(0.0), (VelocityCommand{0.3, 0.0}));
  pipe.write("\x1b[B\x1b[D\x1b[Da");  // Down, Left, Left, a
  EXPECT_EQ(input.poll(0.0), (VelocityCommand{0.2, 0.75}));
  pipe.write("xq\x1b[Z");  // other keys change nothing
  EXPECT_FALSE(input.poll(0.0).has_value());
  pipe.write("d ");
  EXPECT_EQ(input.poll(0.0), (VelocityCommand{0.0, 0.0}));
}

TEST(ScheduledCommandInput, GivesEachRowOnceAtItsTime) {
  const auto path = testing::temp_path("agent_commands.csv");
  testing::write_bytes(path, "time,vx,wz\n0,0,0\n1,0.4,0\n2,0.4,-0.5\n");
  ScheduledCommandInput input(path);
  EXPECT_EQ(input.poll(0.0), (VelocityCommand{0.0, 0.0}));
  EXPECT_FALSE(input.poll(0.5).has_value());
  EXPECT_EQ(input.poll(1.0), (VelocityCommand{0.4, 0.0}));
  EXPECT_FALSE(input.poll(1.99).has_value());
  EXPECT_EQ(input.poll(2.5), (VelocityCommand{0.4, -0.5}));
  testing::write_bytes(path, "0,0,0\n1,zero,0\n");
  EXPECT_THROW(
      {
        try {
          ScheduledCommandInput bad(path);
        } catch (const std::invalid_argument& error) {
          EXPECT_NE(std::string(error.what()).find("agent_commands.csv:2"), std::string::npos)
              << error.what();
          throw;
        }
      },
      std::invalid_argument);
}

}  // namespace
}  // namespace upkie_rl
