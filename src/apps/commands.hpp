#pragma once
/// @file
/// The subcommands of `upkie-rl`, one file each. Each function adds its subcommand to the
/// app; the subcommand runs in its callback and reports failures by throwing
/// std::exception, which main() prints as "upkie-rl: error: ..." with exit code 1.

#include <CLI/CLI.hpp>

namespace upkie_rl::apps {

/// `upkie-rl spine`: a Bullet simulation served over the shared-memory spine link.
void add_spine_command(CLI::App& app);

/// `upkie-rl envs`: the environment ids with their spaces (envs_command.cpp).
void add_envs_command(CLI::App& app);
/// `upkie-rl rollout`: episodes of an environment with a controller (rollout_command.cpp).
void add_rollout_command(CLI::App& app);
/// `upkie-rl drive`: drive a simulated velocity task from the browser.
void add_drive_command(CLI::App& app);

/// `upkie-rl evaluate`: success rates over a grid of perturbations (apps/evaluate_command.cpp).
void add_evaluate_command(CLI::App& app);
/// `upkie-rl view`: the 3-D viewer in the browser, replays and self-contained HTML
/// (view_command.cpp).
void add_view_command(CLI::App& app);
/// `upkie-rl render`: a video of a recorded episode file (render_command.cpp).
void add_render_command(CLI::App& app);
/// `upkie-rl bench`: steps per second of a vector environment (bench_command.cpp).
void add_bench_command(CLI::App& app);
/// `upkie-rl train`: PPO training from a YAML configuration (train_command.cpp).
void add_train_command(CLI::App& app);
/// `upkie-rl sweep`: independent trainings over seeds and settings, and their summary
/// (sweep_command.cpp).
void add_sweep_command(CLI::App& app);
/// `upkie-rl plot`: loss, KL and return figures of a training run (plot_command.cpp).
void add_plot_command(CLI::App& app);
/// `upkie-rl export`: a trained model as ONNX (export_command.cpp).
void add_export_command(CLI::App& app);
/// `upkie-rl identify`: environment options fitted to a robot's log (identify_command.cpp).
void add_identify_command(CLI::App& app);
/// `upkie-rl info`: a model's spaces and provenance (info_command.cpp).
void add_info_command(CLI::App& app);

}  // namespace upkie_rl::apps
