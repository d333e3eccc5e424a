#pragma once
/// @file
/// The root of every error upkie-rl raises on purpose.

#include <stdexcept>

namespace upkie_rl {

/// Base of the domain errors (ModelError, SimulationDivergedError, InvalidCommandError,
/// RenderError, ViewError, SpineError, CheckpointError, PolicyOutputError, OnnxError,
/// DistributedError, AgentError, RecordFileError, RobotLogError, RunFileError,
/// IdentificationError, apps::CommandError): catch it to handle any of
/// them at once. The Python module maps the same hierarchy onto `upkie_rl.Error` (the errors
/// of the layers it binds: not the runner's, the record files' or the robot logs'). Option and
/// configuration mistakes stay `std::invalid_argument` (Python's ValueError).
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace upkie_rl
