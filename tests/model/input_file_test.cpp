#include "base/input_file.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "common/child_call.hpp"
#include "common/temp_files.hpp"
#include "model/robot_model.hpp"

namespace upkie_rl {
namespace {

using testing::child_call_error;
using testing::temp_path;

/// A FIFO in this test program's temporary folder (no writer ever opens it).
std::filesystem::path make_fifo(const std::string& name) {
  const std::filesystem::path path = testing::make_fifo(temp_path(name, "upkie_rl_input_file"));
  EXPECT_FALSE(path.empty()) << name;
  return path;
}

std::string read_error(const std::filesystem::path& path, std::uintmax_t max_bytes) {
  return child_call_error(
      [&] { read_input_file<std::invalid_argument>(path, "test file", max_bytes); });
}

TEST(InputFile, ReadsARegularFileWholeUpToItsLimit) {
  const auto path = temp_path("ten.txt", "upkie_rl_input_file");
  testing::write_bytes(path, "0123456789");
  EXPECT_EQ(read_input_file<std::invalid_argument>(path, "test file", 10), "0123456789");
  const auto empty = temp_path("empty.txt", "upkie_rl_input_file");
  testing::write_bytes(empty, "");
  EXPECT_EQ(read_input_file<std::invalid_argument>(empty, "test file", 10), "");
  EXPECT_EQ(read_error(path, 9),
            "test file " + path.string() + ": 10 bytes, more than the limit of 9 bytes");
}

TEST(InputFile, NamesAMissingFileAndADirectory) {
  const auto missing = temp_path("missing.txt", "upkie_rl_input_file");
  EXPECT_EQ(read_error(missing, 10),
            "test file " + missing.string() + ": cannot open: no such file or directory");
  const auto directory = missing.parent_path();
  EXPECT_EQ(read_error(directory, 10), "test file " + directory.string() + ": is a directory");
}

TEST(InputFile, RefusesADeviceAndAFifoPromptly) {
  const std::string not_regular = ": not a regular file (a FIFO, a device or a socket)";
  EXPECT_EQ(read_error("/dev/zero", std::uintmax_t{1} << 40), "test file /dev/zero" + not_regular);
  const auto fifo = make_fifo("input.fifo");
  EXPECT_EQ(read_error(fifo, 10), "test file " + fifo.string() + not_regular);
}

TEST(InputFile, TheRobotDescriptionRefusesADeviceAndAFifoPromptly) {
  const auto fifo = make_fifo("robot.fifo");
  for (const std::filesystem::path& path : {std::filesystem::path("/dev/zero"), fifo}) {
    EXPECT_EQ(child_call_error([&] { RobotModel::from_urdf_file(path); }),
              "robot description " + path.string() +
                  ": not a regular file (a FIFO, a device or a socket)");
  }
}

}  // namespace
}  // namespace upkie_rl
