/// @file
/// `upkie-rl export MODEL --onnx OUT.onnx`: a trained model as an ONNX policy (raw
/// observation in, clipped deterministic action out; onnx/onnx_export.hpp).

#include <iostream>
#include <memory>
#include <string>

#include "apps/commands.hpp"
#include "cli/option_checks.hpp"
#include "onnx/onnx_export.hpp"

namespace upkie_rl::apps {

namespace {

struct ExportOptions {
  std::string model;
  std::string onnx;
};

}  // namespace

void add_export_command(CLI::App& app) {
  auto options = std::make_shared<ExportOptions>();
  CLI::App* command = app.add_subcommand(
      "export", "Export a trained model for other runtimes (ONNX: raw observation in, action out)");
  command
      ->add_option("model", options->model,
                   "Trained model (model_*.ckpt, a checkpoint, or an imported .ckpt)")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--onnx", options->onnx, "ONNX file to write")
      ->required()
      ->check(kNonEmptyPath);
  command->callback([options] {
    export_onnx_file(options->model, options->onnx);
    std::cout << "wrote " << options->onnx << std::endl;
  });
}

}  // namespace upkie_rl::apps
