#include "onnx/onnx_export.hpp"

#include <onnx/checker.h>
#include <onnx/onnx_pb.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "envs/registry/registry.hpp"
#include "onnx/onnx_error.hpp"
#include "onnx/onnx_metadata.hpp"
#include "policy/build_info.hpp"
#include "policy/checkpoint_file.hpp"
#include "policy/checkpoint_gate.hpp"
#include "policy/mlp.hpp"
#include "policy/provenance.hpp"
#include "policy/space_json.hpp"

namespace upkie_rl {

namespace {

/// Adds the nodes and constants of the graph, naming every value it creates.
class GraphBuilder {
 public:
  explicit GraphBuilder(onnx::GraphProto& graph) : graph_(graph) {}

  /// A float32 constant of shape `dims` (no dims: a scalar).
  std::string constant(const std::string& name, const std::vector<float>& values,
                       const std::vector<std::int64_t>& dims) {
    onnx::TensorProto& tensor = *graph_.add_initializer();
    tensor.set_name(name);
    tensor.set_data_type(onnx::TensorProto::FLOAT);
    for (std::int64_t dim : dims) tensor.add_dims(dim);
    tensor.mutable_float_data()->Add(values.begin(), values.end());
    return name;
  }

  /// A node of `op_type` on `inputs`; returns the name of its one output.
  onnx::NodeProto& node(const std::string& op_type, const std::vector<std::string>& inputs,
                        const std::string& output) {
    onnx::NodeProto& node = *graph_.add_node();
    node.set_op_type(op_type);
    node.set_name(output);
    for (const std::string& input : inputs) node.add_input(input);
    node.add_output(output);
    return node;
  }

  std::string apply(const std::string& op_type, const std::vector<std::string>& inputs,
                    const std::string& output) {
    node(op_type, inputs, output);
    return output;
  }

 private:
  onnx::GraphProto& graph_;
};

void add_tensor_value(onnx::ValueInfoProto& value, const char* name, std::int64_t size) {
  value.set_name(name);
  onnx::TypeProto_Tensor& tensor = *value.mutable_type()->mutable_tensor_type();
  tensor.set_elem_type(onnx::TensorProto::FLOAT);
  tensor.mutable_shape()->add_dim()->set_dim_param(onnx_names::kBatch);
  tensor.mutable_shape()->add_dim()->set_dim_value(size);
}

// (x − mean)/√(var + ε), clipped to ±clip: ObservationNormalizer's formula, with the
// standard deviation computed in double as there.
std::string add_normalization(GraphBuilder& graph, const ObservationNormalizer& normalizer,
                              const std::string& input) {
  if (!normalizer.enabled()) return input;
  const auto size = static_cast<std::int64_t>(normalizer.size());
  std::vector<float> mean;
  std::vector<float> deviation;
  for (std::size_t i = 0; i < normalizer.size(); ++i) {
    mean.push_back(static_cast<float>(normalizer.mean()[i]));
    deviation.push_back(static_cast<float>(std::sqrt(normalizer.var()[i] + normalizer.epsilon())));
  }
  const auto clip = static_cast<float>(normalizer.clip());
  std::string x = graph.apply("Sub", {input, graph.constant("observation_mean", mean, {size})},
                              "centered_observation");
  x = graph.apply("Div", {x, graph.constant("observation_deviation", deviation, {size})},
                  "scaled_observation");
  return graph.apply("Clip",
                     {x, graph.constant("observation_clip_low", {-clip}, {}),
                      graph.constant("observation_clip_high", {clip}, {})},
                     "normalized_observation");
}

onnx::NodeProto& add_float_attribute(onnx::NodeProto& node, const char* name, float value) {
  onnx::AttributeProto& attribute = *node.add_attribute();
  attribute.set_name(name);
  attribute.set_type(onnx::AttributeProto::FLOAT);
  attribute.set_f(value);
  return node;
}

// The activation as ONNX operators of opset 13, with PyTorch's parameters (policy/activation.hpp).
std::string add_activation(GraphBuilder& graph, Activation activation, const std::string& input,
                           const std::string& output) {
  switch (activation) {
    case Activation::kReLU:
      return graph.apply("Relu", {input}, output);
    case Activation::kTanh:
      return graph.apply("Tanh", {input}, output);
    case Activation::kELU:
      add_float_attribute(graph.node("Elu", {input}, output), "alpha", 1.0f);
      return output;
    case Activation::kLeakyReLU:
      add_float_attribute(graph.node("LeakyRelu", {input}, output), "alpha", 0.01f);
      return output;
    case Activation::kSigmoid:
      return graph.apply("Sigmoid", {input}, output);
    case Activation::kSoftplus:
      return graph.apply("Softplus", {input}, output);
    case Activation::kSELU:
      return graph.apply("Selu", {input}, output);  // ONNX's defaults are PyTorch's α and λ.
    case Activation::kSiLU:
      return graph.apply("Mul", {input, graph.apply("Sigmoid", {input}, output + "_sigmoid")},
                         output);
    case Activation::kGELU: {
      // GELU is an operator from opset 20 only: x/2·(1 + erf(x/√2)).
      const std::string scaled =
          graph.apply("Div", {input, graph.constant(output + "_sqrt2", {std::sqrt(2.0f)}, {})},
                      output + "_scaled");
      const std::string erf = graph.apply("Erf", {scaled}, output + "_erf");
      const std::string plus_one = graph.apply(
          "Add", {erf, graph.constant(output + "_one", {1.0f}, {})}, output + "_plus_one");
      const std::string half = graph.apply(
          "Mul", {input, graph.constant(output + "_half", {0.5f}, {})}, output + "_half_x");
      return graph.apply("Mul", {half, plus_one}, output);
    }
  }
  throw OnnxError(std::string("activation ") + activation_name(activation) +
                  " has no ONNX operators");
}

// The actor's dense layers (Gemm: x·Wᵀ + b) with the activation where the Mlp puts it.
std::string add_actor(GraphBuilder& graph, const DeployedPolicy& policy, const std::string& input) {
  const Mlp& actor = policy.actor();
  const std::vector<float>& parameters = policy.parameters();
  std::string x = input;
  for (std::size_t l = 0; l < actor.layers().size(); ++l) {
    const DenseLayerLayout& layer = actor.layers()[l];
    const std::string prefix = "actor_" + std::to_string(l);
    const auto* weights = parameters.data() + layer.weight;
    const auto* biases = parameters.data() + layer.bias;
    const std::string weight = graph.constant(
        prefix + "_weight", {weights, weights + layer.out * layer.in}, {layer.out, layer.in});
    const std::string bias =
        graph.constant(prefix + "_bias", {biases, biases + layer.out}, {layer.out});
    onnx::NodeProto& gemm = graph.node("Gemm", {x, weight, bias}, prefix + "_affine");
    onnx::AttributeProto& transpose = *gemm.add_attribute();
    transpose.set_name("transB");
    transpose.set_type(onnx::AttributeProto::INT);
    transpose.set_i(1);
    x = prefix + "_affine";
    if (actor.activated(l)) {
      x = add_activation(graph, actor.activation(), x, prefix + "_activation");
    }
  }
  return x;
}

std::string add_action_clipping(GraphBuilder& graph, const BoxSpace& space,
                                const std::string& input) {
  const auto size = static_cast<std::int64_t>(space.size());
  const std::string below = graph.apply(
      "Min", {input, graph.constant("action_high", space.high, {size})}, "action_below_high");
  return graph.apply("Max", {below, graph.constant("action_low", space.low, {size})},
                     onnx_names::kAction);
}

// The control frequency: the model's frequency option, else the environment's default.
std::string frequency_of(const DeployedPolicy& policy) {
  for (const auto& [name, value] : policy.env_options()) {
    if (name == "frequency") return value;
  }
  try {
    for (const OptionInfo& option : env_option_info(policy.env_id())) {
      if (option.name == "frequency") return option.default_value;
    }
  } catch (const std::invalid_argument&) {
    // An id this build does not know: the frequency stays unknown.
  }
  return kUnknownProvenance;
}

void add_metadata(onnx::ModelProto& model, const DeployedPolicy& policy,
                  const nlohmann::json& provenance) {
  nlohmann::json options = nlohmann::json::object();
  for (const auto& [name, value] : policy.env_options()) options[name] = value;
  const std::pair<const char*, std::string> entries[] = {
      {onnx_names::kEnvId, policy.env_id()},
      {onnx_names::kEnvOptions, options.dump()},
      {onnx_names::kObservationSpace, space_to_json(policy.observation_space()).dump()},
      {onnx_names::kActionSpace, space_to_json(policy.action_space()).dump()},
      {onnx_names::kFrequency, frequency_of(policy)},
      {onnx_names::kProvenance, provenance.dump()}};
  for (const auto& [key, value] : entries) {
    onnx::StringStringEntryProto& entry = *model.add_metadata_props();
    entry.set_key(key);
    entry.set_value(value);
  }
}

}  // namespace

void export_onnx(const DeployedPolicy& policy, const nlohmann::json& provenance,
                 const std::filesystem::path& path) {
  onnx::ModelProto model;
  model.set_ir_version(onnx::IR_VERSION);
  model.set_producer_name("upkie-rl");
  model.set_producer_version(upkie_rl_version());
  model.set_doc_string("Deterministic policy for " + policy.env_id() +
                       ": raw observation in, clipped action out.");
  onnx::OperatorSetIdProto& opset = *model.add_opset_import();
  opset.set_domain("");
  opset.set_version(kOnnxOpset);
  onnx::GraphProto& graph = *model.mutable_graph();
  graph.set_name("upkie_rl_policy");
  add_tensor_value(*graph.add_input(), onnx_names::kObservation,
                   static_cast<std::int64_t>(policy.observation_space().size()));
  add_tensor_value(*graph.add_output(), onnx_names::kAction,
                   static_cast<std::int64_t>(policy.action_space().size()));
  GraphBuilder builder(graph);
  std::string x = add_normalization(builder, policy.normalizer(), onnx_names::kObservation);
  x = add_actor(builder, policy, x);
  add_action_clipping(builder, policy.action_space(), x);
  add_metadata(model, policy, provenance);
  try {
    onnx::checker::check_model(model);
  } catch (const onnx::checker::ValidationError& error) {
    throw OnnxError("ONNX export for " + path.string() +
                    " fails the ONNX checker: " + error.what());
  }
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  if (!file || !model.SerializeToOstream(&file) || !file.flush()) {
    throw OnnxError("cannot write ONNX model " + path.string());
  }
}

void export_onnx_file(const std::filesystem::path& model_path,
                      const std::filesystem::path& onnx_path) {
  // The checkpoint gate, as for every command; from_checkpoint repeats its (cheap) checks.
  const CheckpointFile file = read_checked_checkpoint(model_path);
  const DeployedPolicy policy =
      DeployedPolicy::from_checkpoint(file, "checkpoint " + model_path.string());
  export_onnx(policy, model_provenance(file.header), onnx_path);
}

}  // namespace upkie_rl
