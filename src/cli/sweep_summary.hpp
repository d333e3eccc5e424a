#pragma once
/// @file
/// The summary of a sweep: one row per run (its final evaluation), one row per setting
/// (mean and spread over the seeds), and the return curves of every run.

#include <string>

#include "rl/runs/sweep_plan.hpp"

namespace upkie_rl::apps {

/// Writes summary.csv (one row per run), summary.md (the two tables) and returns.png (the
/// training return curves, a colour per setting) into the sweep's directory, and returns
/// the tables as Markdown. Runs not finished yet are listed as such. Throws
/// std::runtime_error when gnuplot fails (the tables are written before the figure).
std::string write_sweep_summary(const Sweep& sweep);

}  // namespace upkie_rl::apps
