#pragma once
/// @file
/// The promise of issue 26 for one hostile command line: it is refused cleanly.

#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "apps/cli_runner.hpp"

namespace upkie_rl::testing {

/// `arguments` fails with a status in [1, 127] (1 for errors, CLI11's own for bad flags)
/// within 30 s, in at most three lines, naming `culprit`. A run that hangs is killed after
/// 60 s (status 137, a failure).
inline CliResult expect_clean_refusal(const std::string& arguments, const std::string& culprit) {
  const auto start = std::chrono::steady_clock::now();
  const CliResult result = run_cli(arguments, 60);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_GE(result.exit_code, 1) << arguments << "\n" << result.output;
  EXPECT_LE(result.exit_code, 127) << arguments << "\n" << result.output;
  EXPECT_LE(result.lines().size(), 3u) << arguments << "\n" << result.output;
  EXPECT_NE(result.output.find(culprit), std::string::npos) << arguments << "\n" << result.output;
  EXPECT_LT(seconds, 30.0) << arguments;
  return result;
}

}  // namespace upkie_rl::testing
