// ONNX export: the exported model describes itself (inputs, outputs, metadata) and passes
// the ONNX checker; damaged, foreign or oversized ONNX files are refused with the file named.
// (onnxruntime runs the exports against DeployedPolicy in python/tests/test_onnx_export.py.)

#include <gtest/gtest.h>
#include <onnx/onnx_pb.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "common/temp_files.hpp"
#include "onnx/onnx_error.hpp"
#include "onnx/onnx_export.hpp"
#include "onnx/onnx_metadata.hpp"
#include "onnx/onnx_model_info.hpp"

namespace upkie_rl {
namespace {

const std::filesystem::path kPolicies = std::filesystem::path(UPKIE_RL_TEST_DATA_DIR) / "policies";

std::filesystem::path exported(const std::string& name) {
  const std::filesystem::path path = testing::temp_path(name + ".onnx");
  export_onnx_file(kPolicies / (name + ".ckpt"), path);
  return path;
}

TEST(OnnxExport, PendulumModelHasOneBatchedInputAndOutputAndItsMetadata) {
  const OnnxModelInfo info = read_onnx_model_info(exported("pendulum_mujoco_seed0"));
  EXPECT_EQ(info.producer_name, "upkie-rl");
  EXPECT_EQ(info.opset, kOnnxOpset);
  ASSERT_EQ(info.inputs.size(), 1u);
  ASSERT_EQ(info.outputs.size(), 1u);
  EXPECT_EQ(info.inputs[0].name, onnx_names::kObservation);
  EXPECT_EQ(info.inputs[0].element_type, "FLOAT");
  EXPECT_EQ(info.inputs[0].shape, (std::vector<std::string>{"batch", "4"}));
  EXPECT_EQ(info.outputs[0].name, onnx_names::kAction);
  EXPECT_EQ(info.outputs[0].shape, (std::vector<std::string>{"batch", "1"}));
  EXPECT_EQ(info.metadata.at(onnx_names::kEnvId), "Upkie-MuJoCo-Pendulum");
  EXPECT_EQ(info.metadata.at(onnx_names::kFrequency), "200");
  const auto space = nlohmann::json::parse(info.metadata.at(onnx_names::kObservationSpace));
  EXPECT_EQ(space.at("names").size(), 4u);
  const auto provenance = nlohmann::json::parse(info.metadata.at(onnx_names::kProvenance));
  EXPECT_EQ(provenance.at("env_id"), "Upkie-MuJoCo-Pendulum");
  EXPECT_EQ(provenance.at("seed"), "0");
  EXPECT_EQ(provenance.at("timesteps").get<std::int64_t>() >= 1'000'000, true);
  // Written before provenance existed: what it cannot know says so.
  EXPECT_EQ(provenance.at("git_commit"), "unknown");
}

TEST(OnnxExport, ServosBalanceModelExportsItsLargerSpaces) {
  const OnnxModelInfo info = read_onnx_model_info(exported("servos_balance_mujoco_seed0"));
  ASSERT_EQ(info.inputs.size(), 1u);
  EXPECT_GT(std::stoi(info.inputs[0].shape[1]), 4);
  EXPECT_NE(info.metadata.at(onnx_names::kFrequency), "unknown");
}

TEST(OnnxExport, ABadModelIsRefusedBeforeAnythingIsWritten) {
  const std::filesystem::path bad = testing::temp_path("bad_model.ckpt");
  testing::write_bytes(bad, "UPKIERL1 then nothing");
  const std::filesystem::path out = testing::temp_path("never.onnx");
  EXPECT_THROW(export_onnx_file(bad, out), CheckpointError);
  EXPECT_FALSE(std::filesystem::exists(out));
}

void expect_refused(const std::filesystem::path& path, const std::string& reason) {
  try {
    read_onnx_model_info(path);
    FAIL() << "accepted " << path;
  } catch (const OnnxError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(path.filename().string()), std::string::npos) << message;
    EXPECT_NE(message.find(reason), std::string::npos) << message;
  }
}

TEST(OnnxModelInfo, RefusesMissingEmptyForeignAndTruncatedFiles) {
  expect_refused(testing::temp_path("missing.onnx"), "cannot open");
  const std::filesystem::path empty = testing::temp_path("empty.onnx");
  testing::write_bytes(empty, "");
  expect_refused(empty, "not an ONNX model");
  const std::filesystem::path text = testing::temp_path("text.onnx");
  testing::write_bytes(text, "this is plain text, not a protobuf\n");
  expect_refused(text, "not an ONNX model");
  const std::string whole = testing::read_bytes(exported("pendulum_bullet_seed0"));
  for (const std::size_t size : {whole.size() / 2, whole.size() - 3}) {
    const std::filesystem::path truncated = testing::temp_path("truncated.onnx");
    testing::write_bytes(truncated, whole.substr(0, size));
    expect_refused(truncated, "ONNX model");
  }
}

TEST(OnnxModelInfo, RefusesAModelTheCheckerRejects) {
  onnx::ModelProto model;
  model.set_ir_version(onnx::IR_VERSION);
  model.add_opset_import()->set_version(kOnnxOpset);
  onnx::NodeProto& node = *model.mutable_graph()->add_node();
  node.set_op_type("NoSuchOperator");
  node.add_input("x");
  node.add_output("y");
  const std::filesystem::path path = testing::temp_path("invalid.onnx");
  std::ofstream file(path, std::ios::binary);
  model.SerializeToOstream(&file);
  file.close();
  expect_refused(path, "invalid");
}

TEST(OnnxModelInfo, RefusesAFileLargerThanAnyPolicyWithoutReadingIt) {
  const std::filesystem::path path = testing::temp_path("huge.onnx");
  testing::write_bytes(path, "");
  std::filesystem::resize_file(path, kMaxOnnxFileBytes + 1);  // Sparse: no disk used.
  expect_refused(path, "more than");
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace upkie_rl
