/// `upkie-rl view`, `rollout --view`: replays, self-contained pages and errors, from the
/// real binary. (The pages themselves are tested in a browser: web/viewer/tests.)

#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "apps/cli_runner.hpp"
#include "common/temp_files.hpp"

namespace upkie_rl {
namespace {

using testing::read_bytes;
using testing::run_cli;
using testing::temp_path;
using testing::write_bytes;

/// The session a self-contained page holds.
nlohmann::json session_of_page(const std::string& page) {
  const std::string open = "<script id=\"upkie-session\" type=\"application/json\">";
  const std::size_t begin = page.find(open);
  if (begin == std::string::npos) return {};
  const std::size_t end = page.find("</script>", begin);
  return nlohmann::json::parse(page.substr(begin + open.size(), end - begin - open.size()));
}

/// A listening socket on a free port of 127.0.0.1, closed at destruction.
class BusyPort {
 public:
  BusyPort() {
    fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ::bind(fd_, reinterpret_cast<sockaddr*>(&address), sizeof(address));
    ::listen(fd_, 1);
    socklen_t length = sizeof(address);
    ::getsockname(fd_, reinterpret_cast<sockaddr*>(&address), &length);
    port_ = ntohs(address.sin_port);
  }
  ~BusyPort() { ::close(fd_); }
  int port() const { return port_; }

 private:
  int fd_ = -1;
  int port_ = 0;
};

class ViewCommand : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    record_ = new std::filesystem::path(temp_path("two_episodes.csv"));
    const auto result = run_cli(
        "rollout --env Upkie-Bullet-Pendulum --controller linear:10,1,0,0.1 --episodes 2 "
        "--max-steps 30 --env-option init_rand_pitch=0.1 --record " +
        record_->string());
    ASSERT_EQ(result.exit_code, 0) << result.output;
  }
  static void TearDownTestSuite() {
    std::filesystem::remove(*record_);
    delete record_;
  }
  static std::filesystem::path* record_;
};
std::filesystem::path* ViewCommand::record_ = nullptr;

TEST_F(ViewCommand, HtmlHoldsEveryRecordedStep) {
  const auto html = temp_path("replay.html");
  const auto result = run_cli("view " + record_->string() + " --html " + html.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("2 episode(s), 60 steps, actions: ground_velocity"),
            std::string::npos)
      << result.output;
  const nlohmann::json session = session_of_page(read_bytes(html));
  ASSERT_FALSE(session.is_null());
  EXPECT_EQ(session["mode"], "replay");
  EXPECT_DOUBLE_EQ(session["timestep"].get<double>(), 0.005);
  const auto fields = session["frame_fields"].get<std::vector<std::string>>();
  ASSERT_EQ(session["episodes"].size(), 2u);
  const auto frames = session["episodes"][1]["frames"].get<std::vector<double>>();
  ASSERT_EQ(frames.size(), 30 * fields.size());
  const auto column = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(fields.begin(), fields.end(), name) - fields.begin());
  };
  // Episode 1 starts tilted (init_rand_pitch) and at 0 return; its 11th frame is at 50 ms.
  EXPECT_EQ(frames[column("episode")], 1.0);
  EXPECT_EQ(frames[column("return")], 0.0);
  EXPECT_NE(frames[column("pitch")], 0.0);
  EXPECT_NEAR(frames[10 * fields.size() + column("time")], 0.05, 1e-9);
  EXPECT_NE(frames[10 * fields.size() + column("return")], 0.0);
  EXPECT_NEAR(frames[column("base_z")], 0.6, 0.05);
  EXPECT_LT(column("action.ground_velocity"), fields.size());
  std::filesystem::remove(html);
}

TEST_F(ViewCommand, RecordsOfEarlierVersionsStillReplay) {
  // Without the pitch and ground_position columns: pitch from the base orientation.
  std::ifstream in(*record_);
  std::string line, old_format;
  while (std::getline(in, line))
    old_format += line.substr(0, line.rfind(',', line.rfind(',') - 1)) + "\n";
  const auto old_record = temp_path("old_format.csv");
  write_bytes(old_record, old_format);
  const auto html = temp_path("old_format.html");
  const auto result = run_cli("view " + old_record.string() + " --html " + html.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json session = session_of_page(read_bytes(html));
  const auto fields = session["frame_fields"].get<std::vector<std::string>>();
  const auto pitch = std::find(fields.begin(), fields.end(), "pitch") - fields.begin();
  EXPECT_NEAR(session["episodes"][0]["frames"][pitch].get<double>(), 0.0984, 0.05);
  std::filesystem::remove(old_record);
  std::filesystem::remove(html);
}

TEST_F(ViewCommand, WithoutARecordShowsTheRobotAtRest) {
  const auto html = temp_path("rest.html");
  const auto result = run_cli("view --html " + html.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json session = session_of_page(read_bytes(html));
  ASSERT_EQ(session["episodes"].size(), 1u);
  EXPECT_EQ(session["episodes"][0]["frames"].size(), session["frame_fields"].size());
  std::filesystem::remove(html);
}

TEST_F(ViewCommand, NamesWhatIsWrongWithARecord) {
  std::ifstream in(*record_);
  std::string header, row;
  std::getline(in, header);
  std::getline(in, row);
  const auto html = temp_path("never.html");
  struct Case {
    std::string name, text, expected;
  };
  const std::vector<Case> cases = {
      {"empty.csv", "", "is empty"},
      {"header_only.csv", header + "\n", "has a header but no rows"},
      {"unknown_layout.csv", "time,x,y\n0,1,2\n", "no column \"episode\""},
      {"truncated.csv", header + "\n" + row + "\n" + row.substr(0, row.size() / 2),
       ":3: " + std::to_string(1 + std::count(row.begin(), row.begin() + row.size() / 2, ',')) +
           " fields, the header has"},
      {"not_a_number.csv",
       header + "\n" + row.substr(0, row.find(",0.6,")) + ",high" +
           row.substr(row.find(",0.6,") + 4) + "\n",
       "column base_z is not a number: \"high\""},
      {"fractional_step.csv", header + "\n0,0.5" + row.substr(row.find(',', 2)) + "\n",
       "episode and step must be whole numbers"},
  };
  for (const Case& test : cases) {
    const auto path = temp_path(test.name);
    write_bytes(path, test.text);
    const auto result = run_cli("view " + path.string() + " --html " + html.string());
    EXPECT_EQ(result.exit_code, 1) << test.name;
    EXPECT_NE(result.output.find(test.expected), std::string::npos)
        << test.name << ": " << result.output;
    EXPECT_NE(result.output.find(path.string()), std::string::npos) << result.output;
    std::filesystem::remove(path);
  }
  EXPECT_FALSE(std::filesystem::exists(html));
}

TEST_F(ViewCommand, NamesABusyPortAndKeepsAnExistingRecord) {
  const BusyPort busy;
  const std::string port = std::to_string(busy.port());
  auto result = run_cli("view " + record_->string() + " --view-port " + port);
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find("cannot listen on 127.0.0.1:" + port + ": the port is in use"),
            std::string::npos)
      << result.output;

  const auto kept = temp_path("kept.csv");
  write_bytes(kept, "precious\n");
  result = run_cli("rollout --env Upkie-Bullet-Pendulum --view --view-port " + port + " --record " +
                   kept.string());
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find("the port is in use"), std::string::npos) << result.output;
  EXPECT_EQ(read_bytes(kept), "precious\n");
  std::filesystem::remove(kept);
}

TEST_F(ViewCommand, AnUnpacedLiveRolloutWithoutBrowsersRunsToTheEnd) {
  const auto result = run_cli(
      "rollout --env Upkie-Bullet-Pendulum --controller linear:10,1,0,0.1 --episodes 2 "
      "--max-steps 50 --view --view-port 0 --view-speed 0");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("viewer: http://127.0.0.1:"), std::string::npos);
  EXPECT_NE(result.output.find("mean return"), std::string::npos);
}

}  // namespace
}  // namespace upkie_rl
