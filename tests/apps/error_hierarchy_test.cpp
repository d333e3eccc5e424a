// Every domain error derives from the one root, upkie_rl::Error (base/error.hpp).

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "agent/agent_error.hpp"
#include "base/error.hpp"
#include "cli/command_error.hpp"
#include "envs/records/record_file_error.hpp"
#include "identify/identification_error.hpp"
#include "model/robot_model.hpp"
#include "onnx/onnx_error.hpp"
#include "policy/checkpoint_file.hpp"
#include "policy/deployed_policy.hpp"
#include "policy/policy_output_error.hpp"
#include "render/render_error.hpp"
#include "rl/distributed/communicator.hpp"
#include "rl/runs/run_file_error.hpp"
#include "sim/servo_command.hpp"
#include "sim/simulation.hpp"
#include "spine/spine_error.hpp"
#include "view/view_error.hpp"

namespace upkie_rl {
namespace {

template <class... Errors>
constexpr bool all_derive_from_error() {
  return (std::is_base_of_v<Error, Errors> && ...);
}

TEST(ErrorHierarchy, EveryDomainErrorHasTheOneRoot) {
  static_assert(std::is_base_of_v<std::runtime_error, Error>);
  static_assert(all_derive_from_error<ModelError, CheckpointError, SimulationDivergedError,
                                      InvalidCommandError, RenderError, DistributedError, ViewError,
                                      SpineError, SpineTimeoutError, OnnxError, AgentError,
                                      SupervisorTrip, RecordFileError, PolicyOutputError,
                                      RunFileError, IdentificationError, apps::CommandError>());
  // Not an option mistake: those stay std::invalid_argument.
  static_assert(!std::is_base_of_v<std::invalid_argument, InvalidCommandError>);
}

TEST(ErrorHierarchy, RealFailuresAreCaughtAsTheRoot) {
  ServoAction action{};
  action[0].velocity = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(validate_servo_action(action), Error);
  const std::filesystem::path garbage =
      std::filesystem::temp_directory_path() / "upkie_rl_error_hierarchy_test.ckpt";
  std::ofstream(garbage) << "not a checkpoint";
  try {
    DeployedPolicy::load(garbage);
    FAIL() << "expected an error";
  } catch (const Error& error) {
    EXPECT_NE(dynamic_cast<const CheckpointError*>(&error), nullptr);
    EXPECT_NE(std::string(error.what()).find("bad magic"), std::string::npos);
  }
  std::filesystem::remove(garbage);
}

// Every error the code raises on purpose is a domain error or an option mistake
// (std::invalid_argument); a bare std::runtime_error would escape `except upkie_rl.Error`
// and the error-kind tables.
TEST(ErrorHierarchy, NoBareRuntimeErrorIsThrown) {
  const std::filesystem::path sources = std::filesystem::path(UPKIE_RL_SOURCE_DIR) / "src";
  std::vector<std::string> throwing;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(sources)) {
    const std::string extension = entry.path().extension().string();
    if (extension != ".cpp" && extension != ".hpp") continue;
    std::stringstream text;
    text << std::ifstream(entry.path()).rdbuf();
    if (text.str().find("throw std::runtime_error(") != std::string::npos) {
      throwing.push_back(entry.path().lexically_relative(sources).string());
    }
  }
  EXPECT_TRUE(throwing.empty()) << "throw std::runtime_error in "
                                << ::testing::PrintToString(throwing);
}

}  // namespace
}  // namespace upkie_rl
