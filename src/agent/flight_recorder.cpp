#include "agent/flight_recorder.hpp"

#include <string>

namespace upkie_rl {

void FlightRecorder::write_header(const Env& env) {
  const std::array<std::string, kFlightRecorderColumns.size()> columns = {
      kFlightRecorderColumns[0], kFlightRecorderColumns[1], kFlightRecorderColumns[2],
      kFlightRecorderColumns[3]};
  recorder_.write_header(env, columns);
}

void FlightRecorder::after_step(int cycle, std::span<const float> action, const StepResult& result,
                                SupervisorState state, double loop_period, double policy_time,
                                bool deadline_miss) {
  const std::array<double, kFlightRecorderColumns.size()> values = {
      static_cast<double>(state), loop_period, policy_time, deadline_miss ? 1.0 : 0.0};
  recorder_.after_step(0, cycle, action, result, values);
}

}  // namespace upkie_rl
