/// @file
/// Entry point of the `upkie-rl` command-line tool.

#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <string>

#include "apps/commands.hpp"
#include "policy/build_info.hpp"

namespace {

int run(int argc, char** argv) {
  CLI::App app{
      "upkie-rl: simulate, train, evaluate and deploy balance controllers for Upkie, "
      "the open-source wheeled biped."};
  app.set_version_flag("--version", std::string("upkie-rl ") + upkie_rl::upkie_rl_version() +
                                        " (commit " + upkie_rl::upkie_rl_git_commit() + ")");
  app.require_subcommand(1);
  app.fallthrough(false);
  upkie_rl::apps::add_envs_command(app);
  upkie_rl::apps::add_rollout_command(app);
  upkie_rl::apps::add_drive_command(app);
  upkie_rl::apps::add_evaluate_command(app);
  upkie_rl::apps::add_render_command(app);
  upkie_rl::apps::add_view_command(app);
  upkie_rl::apps::add_bench_command(app);
  upkie_rl::apps::add_spine_command(app);
  upkie_rl::apps::add_train_command(app);
  upkie_rl::apps::add_sweep_command(app);
  upkie_rl::apps::add_plot_command(app);
  upkie_rl::apps::add_export_command(app);
  upkie_rl::apps::add_info_command(app);
  upkie_rl::apps::add_identify_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app.exit(error);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // Every failure, setting up the commands included, ends as one line and status 1.
  try {
    return run(argc, argv);
  } catch (const std::exception& error) {
    std::cerr << "upkie-rl: error: " << error.what() << std::endl;
  } catch (...) {
    std::cerr << "upkie-rl: error: unknown exception" << std::endl;
  }
  return 1;
}
