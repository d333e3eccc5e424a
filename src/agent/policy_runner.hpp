#pragma once
/// @file
/// run_policy: the robot runner's whole run, from the checkpoint to the detached spine.

#include <atomic>

#include "agent/run_summary.hpp"
#include "agent/runner_options.hpp"

namespace upkie_rl {

/// Loads the policy, attaches to the spine, and runs the policy at its task's frequency on
/// the spine backend of the environment it was trained on (the same task code as in
/// training), under the supervisor, until the duration, `interrupt` (set by SIGINT or
/// SIGTERM), a limit or an error. Every way out goes through stopping (stop commands, then
/// Stop) to stopped. `interrupt` is cleared when stopping begins, so that the interrupt that
/// caused the stop does not count: one set during the stop commands (an operator's second
/// Ctrl-C) cuts them short, the Stop request following at once (summary.stop_cut_short).
/// Never throws: errors become the summary's stop reason.
RunSummary run_policy(const RunnerOptions& options, std::atomic<bool>& interrupt);

}  // namespace upkie_rl
