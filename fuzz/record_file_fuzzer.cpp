/// @file
/// libFuzzer target: the record files of `upkie-rl rollout --record`, as `upkie-rl render`
/// and `upkie-rl view` read them (envs/records/record_file.hpp). Each input is a whole file, read
/// from memory. Refusing it with RecordFileError is the expected outcome; a crash, a hang,
/// a sanitizer report or another exception is a bug. Whatever is accepted must hold what
/// the renderer and the viewer rely on: at least one row, finite times and base poses, a
/// non-zero orientation, whole episode and step numbers, one action value per action
/// column, and a command and measured velocity on every row exactly when the file has them.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>

#include "envs/records/record_file.hpp"

namespace {

void check_accepted(const upkie_rl::RecordFile& file) {
  if (file.steps.empty()) std::abort();
  for (const upkie_rl::RecordedStep& step : file.steps) {
    const upkie_rl::RobotPose& pose = step.pose;
    if (step.episode < 0 || step.step < 0 || !std::isfinite(step.time) ||
        !pose.base_position.allFinite() || !pose.base_orientation.coeffs().allFinite() ||
        !(pose.base_orientation.norm() > 0.0)) {
      std::abort();
    }
    if (step.action.size() != file.action_names.size()) std::abort();
    if (step.command.has_value() != file.has_velocity() ||
        step.measured.has_value() != file.has_velocity()) {
      std::abort();
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try {
    check_accepted(upkie_rl::read_record_file(in, "input.csv"));
  } catch (const upkie_rl::RecordFileError&) {
  }
  return 0;
}
