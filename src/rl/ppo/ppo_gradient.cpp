#include "rl/ppo/ppo_gradient.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "policy/diagonal_gaussian.hpp"
#include "rl/ppo/dense_layer_backward_avx2.hpp"
#include "rl/ppo/hand_gradient_activations.hpp"
#include "rl/ppo/matrix_kernels_avx2.hpp"
#include "rl/ppo/tensor_span.hpp"

namespace upkie_rl {

namespace {

using RowMatrix = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using MatrixMap = Eigen::Map<RowMatrix>;
using ConstMatrixMap = Eigen::Map<const RowMatrix>;
using RowVectorMap = Eigen::Map<Eigen::RowVectorXf>;
using ConstRowVectorMap = Eigen::Map<const Eigen::RowVectorXf>;

std::span<const float> tensor_span(const torch::Tensor& tensor, const char* name) {
  if (!tensor.defined() || tensor.scalar_type() != torch::kFloat32 || !tensor.is_cpu() ||
      !tensor.is_contiguous()) {
    throw std::invalid_argument(std::string("PPO minibatch: '") + name +
                                "' must be a contiguous float32 CPU tensor");
  }
  return tensor_values(tensor);
}

void check_span(std::span<const float> span, std::int64_t expected, const char* name) {
  if (static_cast<std::int64_t>(span.size()) != expected) {
    throw std::invalid_argument(std::string("PpoGradient: '") + name + "' has " +
                                std::to_string(span.size()) + " values, expected " +
                                std::to_string(expected));
  }
}

// The most values one row of a layer's input or output holds in `mlp`.
std::int64_t widest_layer(const Mlp& mlp) {
  std::int64_t width = 1;
  for (const DenseLayerLayout& layer : mlp.layers()) width = std::max({width, layer.in, layer.out});
  return width;
}

// The most weights a layer of `mlp` has.
std::int64_t largest_weight(const Mlp& mlp) {
  std::int64_t weights = 0;
  for (const DenseLayerLayout& layer : mlp.layers()) {
    weights = std::max(weights, layer.in * layer.out);
  }
  return weights;
}

}  // namespace

PpoMinibatchView PpoMinibatchView::rows(std::int64_t begin, std::int64_t length) const {
  if (begin < 0 || length < 0 || begin + length > size) {
    throw std::out_of_range("PpoMinibatchView: rows [" + std::to_string(begin) + ", " +
                            std::to_string(begin + length) + ") of " + std::to_string(size));
  }
  const auto slice = [&](std::span<const float> all) {
    const auto width = static_cast<std::size_t>(all.size() / static_cast<std::size_t>(size));
    return all.subspan(static_cast<std::size_t>(begin) * width,
                       static_cast<std::size_t>(length) * width);
  };
  return {length,
          slice(observations),
          slice(actions),
          slice(old_log_prob),
          slice(old_values),
          slice(advantages),
          slice(returns)};
}

PpoMinibatchView view_minibatch(const PpoMinibatch& batch) {
  PpoMinibatchView view;
  view.observations = tensor_span(batch.observations, "observations");
  view.actions = tensor_span(batch.actions, "actions");
  view.old_log_prob = tensor_span(batch.old_log_prob, "old_log_prob");
  view.old_values = tensor_span(batch.old_values, "old_values");
  view.advantages = tensor_span(batch.advantages, "advantages");
  view.returns = tensor_span(batch.returns, "returns");
  view.size = static_cast<std::int64_t>(view.old_log_prob.size());
  return view;
}

bool PpoGradient::covers(Activation activation) { return hand_gradient_covers(activation); }

PpoGradient::NetworkScratch::NetworkScratch(const Mlp& mlp, std::int64_t max_batch_size) {
  const auto rows = static_cast<std::size_t>(max_batch_size);
  for (const DenseLayerLayout& layer : mlp.layers()) {
    outputs.emplace_back(rows * static_cast<std::size_t>(layer.out));
  }
  output_gradient.resize(rows * static_cast<std::size_t>(widest_layer(mlp)));
  input_gradient.resize(output_gradient.size());
  transposed_weight.resize(static_cast<std::size_t>(largest_weight(mlp)));
}

namespace {

// The policy's networks, after checking what PpoGradient can compute with them.
ActorCriticNetworks checked_networks(const ActorCritic& policy, std::int64_t max_batch_size,
                                     std::int64_t update_threads) {
  if (max_batch_size < 1) throw std::invalid_argument("PpoGradient: max_batch_size must be >= 1");
  if (update_threads != 1 && update_threads != 2) {
    throw std::invalid_argument("PpoGradient: ppo.update_threads must be 1 or 2, got " +
                                std::to_string(update_threads));
  }
  if (!hand_gradient_covers(policy.config().activation)) {
    throw std::invalid_argument(std::string("PpoGradient: the hand-written gradient covers relu "
                                            "and tanh, not ") +
                                activation_name(policy.config().activation) +
                                " (train with ppo.gradient: " + "autograd)");
  }
  return actor_critic_networks(policy.observation_size(), policy.action_size(),
                               policy.config().actor_hidden_sizes,
                               policy.config().critic_hidden_sizes, policy.config().activation);
}

}  // namespace

PpoGradient::PpoGradient(const ActorCritic& policy, std::int64_t max_batch_size,
                         PpoGradientKernel kernel, std::int64_t update_threads)
    : avx2_(kernel == PpoGradientKernel::kFastest && cpu_has_avx2_fma()),
      max_batch_size_(max_batch_size),
      networks_(checked_networks(policy, max_batch_size, update_threads)),
      actor_(networks_.actor, max_batch_size),
      critic_(networks_.critic, max_batch_size),
      log_prob_gradient_(static_cast<std::size_t>(max_batch_size)),
      advantages_(static_cast<std::size_t>(max_batch_size)),
      companion_(update_threads == 2 ? std::make_unique<CompanionThread>() : nullptr) {}

void PpoGradient::forward(const Mlp& mlp, NetworkScratch& scratch, const float* parameters,
                          const float* input, std::int64_t rows) const {
  const bool relu = mlp.activation() == Activation::kReLU;  // else tanh: covers() allows no other
  const float* x = input;
  for (std::size_t i = 0; i < mlp.layers().size(); ++i) {
    const DenseLayerLayout& layer = mlp.layers()[i];
    const bool hidden = mlp.activated(i);
    const ConstMatrixMap in(x, rows, layer.in);
    const ConstMatrixMap weight(parameters + layer.weight, layer.out, layer.in);
    float* y_data = scratch.outputs[i].data();
    MatrixMap y(y_data, rows, layer.out);
    if (avx2_) {
      // y = x·Wᵀ + b with Wᵀ copied row-major (in x out) for the kernel.
      transpose_avx2(weight.data(), layer.out, layer.in, scratch.transposed_weight.data());
      gemm_avx2({.m = rows,
                 .n = layer.out,
                 .k = layer.in,
                 .a = x,
                 .a_row_stride = layer.in,
                 .a_depth_stride = 1,
                 .b = scratch.transposed_weight.data(),
                 .ldb = layer.out,
                 .c = y_data,
                 .ldc = layer.out,
                 .bias = parameters + layer.bias,
                 .epilogue = hidden && relu ? GemmEpilogue::kRelu : GemmEpilogue::kNone});
      if (hidden && !relu) y = y.array().tanh().matrix();
    } else {
      y.noalias() = in * weight.transpose();
      y.rowwise() += ConstRowVectorMap(parameters + layer.bias, layer.out);
      if (hidden) {
        if (relu) {
          y = y.cwiseMax(0.0f);
        } else {
          y = y.array().tanh().matrix();
        }
      }
    }
    x = y_data;
  }
}

void PpoGradient::backward(const Mlp& mlp, NetworkScratch& scratch, const float* parameters,
                           const float* input, std::int64_t rows, float* gradients) const {
  const bool relu = mlp.activation() == Activation::kReLU;  // else tanh: covers() allows no other
  // scratch.output_gradient holds ∂L/∂(output of the last layer) on entry, and ∂L/∂z
  // (before the activation) of the layer below at the end of each iteration. Through the
  // activation, from its output y: relu passes the gradient where y > 0 (none at 0, like
  // torch's threshold_backward); tanh' = 1 − y².
  // Every layer below the output layer is activated (Mlp::activated).
  for (std::size_t k = mlp.layers().size(); k-- > 0;) {
    const DenseLayerLayout& layer = mlp.layers()[k];
    const float* in_data = k == 0 ? input : scratch.outputs[k - 1].data();
    const ConstMatrixMap in(in_data, rows, layer.in);
    const ConstMatrixMap weight(parameters + layer.weight, layer.out, layer.in);
    MatrixMap d_output(scratch.output_gradient.data(), rows, layer.out);
    MatrixMap d_weight(gradients + layer.weight, layer.out, layer.in);
    RowVectorMap d_bias(gradients + layer.bias, layer.out);
    MatrixMap d_input(scratch.input_gradient.data(), rows, layer.in);
    if (!avx2_) {
      d_bias = d_output.colwise().sum();
      d_weight.noalias() = d_output.transpose() * in;
      if (k > 0) {
        // Through the activation of the layer below, whose output y is our input.
        d_input.noalias() = d_output * weight;
        if (relu) {
          d_input.array() = (in.array() > 0.0f).select(d_input.array(), 0.0f);
        } else {
          d_input.array() *= 1.0f - in.array().square();
        }
      }
    } else {
      backward_layer_avx2({.layer = layer,
                           .rows = rows,
                           .input = in_data,
                           .weight = weight.data(),
                           .d_output = d_output.data(),
                           .gate = k > 0 ? in_data : nullptr,
                           .relu = relu,
                           .scratch = scratch.transposed_weight.data(),
                           .d_weight = d_weight.data(),
                           .d_bias = d_bias.data(),
                           .d_input = d_input.data()});
    }
    if (k > 0) std::swap(scratch.output_gradient, scratch.input_gradient);  // Pointers only.
  }
}

bool PpoGradient::same_shape(const ActorCritic& policy) const {
  const PolicyConfig& config = policy.config();
  // The hidden widths, then the output layer.
  const auto same_widths = [](const Mlp& mlp, const std::vector<std::int64_t>& hidden) {
    const std::vector<DenseLayerLayout>& layers = mlp.layers();
    if (hidden.size() + 1 != layers.size()) return false;
    for (std::size_t i = 0; i < hidden.size(); ++i) {
      if (hidden[i] != layers[i].out) return false;
    }
    return true;
  };
  return policy.observation_size() == networks_.actor.input_size() &&
         policy.action_size() == networks_.actor.output_size() &&
         config.activation == networks_.actor.activation() &&
         same_widths(networks_.actor, config.actor_hidden_sizes) &&
         same_widths(networks_.critic, config.critic_hidden_sizes) &&
         policy.flat_parameters().numel() == networks_.size;
}

namespace {

// Advantages into `out`, normalised over the minibatch like compute_ppo_loss (unbiased std)
// when `normalize` and there is more than one.
void normalise_advantages(std::span<const float> advantages, bool normalize, float* out) {
  const auto n = static_cast<std::int64_t>(advantages.size());
  if (!normalize || n < 2) {
    std::copy_n(advantages.data(), n, out);
    return;
  }
  double sum = 0.0;
  for (std::int64_t i = 0; i < n; ++i) sum += advantages[i];
  const double mean = sum / static_cast<double>(n);
  double squares = 0.0;
  for (std::int64_t i = 0; i < n; ++i) {
    const double d = advantages[i] - mean;
    squares += d * d;
  }
  const double scale = 1.0 / (std::sqrt(squares / static_cast<double>(n - 1)) + 1e-8);
  for (std::int64_t i = 0; i < n; ++i) {
    out[i] = static_cast<float>((advantages[i] - mean) * scale);
  }
}

// The actor's outputs and log σ, read by the policy term.
struct GaussianPolicy {
  const float* means;    // n x action_size, row-major.
  const float* log_std;  // action_size.
  std::int64_t action_size;
};

// Sums over the minibatch of the clipped surrogate min(A·ρ, A·clamp(ρ)), of the KL estimate
// (ρ − 1) − log ρ, and the count of ratios outside 1 ± ε.
struct SurrogateSums {
  double surrogate = 0.0;
  double kl = 0.0;
  std::int64_t clipped = 0;
};

// The policy term: its sums, and ∂L/∂log π(a|s) of each sample into `log_prob_gradient`.
// log π = −½Σ z² − log_normaliser (policy/diagonal_gaussian.hpp) with z = (a − μ)/σ.
SurrogateSums surrogate_term(const PpoMinibatchView& batch, const GaussianPolicy& policy,
                             const float* advantages, const PpoConfig& config,
                             double* log_prob_gradient) {
  const std::int64_t n = batch.size;
  const std::int64_t a_size = policy.action_size;
  const double log_normaliser = gaussian_log_normaliser(
      std::span<const float>(policy.log_std, static_cast<std::size_t>(a_size)));
  // Float bounds, as torch compares float tensors with the double scalars cast to float.
  const float low = static_cast<float>(1.0 - config.clip_range);
  const float high = static_cast<float>(1.0 + config.clip_range);
  const float clip_range = static_cast<float>(config.clip_range);
  const double inverse_n = 1.0 / static_cast<double>(n);
  SurrogateSums sums;
  for (std::int64_t i = 0; i < n; ++i) {
    const float* action = batch.actions.data() + i * a_size;
    const float* mean = policy.means + i * a_size;
    double squares = 0.0;
    for (std::int64_t j = 0; j < a_size; ++j) {
      const float z = (action[j] - mean[j]) * std::exp(-policy.log_std[j]);
      squares += static_cast<double>(z) * z;
    }
    const double log_ratio =
        gaussian_log_probability(squares, log_normaliser) - batch.old_log_prob[i];
    const double ratio = std::exp(log_ratio);
    sums.kl += (ratio - 1.0) - log_ratio;
    const float ratio_f = static_cast<float>(ratio);
    if (std::abs(ratio_f - 1.0f) > clip_range) ++sums.clipped;
    // min(A·ρ, A·clamp(ρ)) with torch's gradient rules: the smaller operand takes the
    // whole gradient, equal operands half each (the usual case: ρ inside the range);
    // clamp passes the gradient inside [low, high], bounds included.
    const float advantage = advantages[i];
    const float surrogate = advantage * ratio_f;
    const float clipped = advantage * std::clamp(ratio_f, low, high);
    sums.surrogate += std::min(surrogate, clipped);
    double surrogate_weight = 0.5, clipped_weight = 0.5;
    if (surrogate < clipped) {
      surrogate_weight = 1.0, clipped_weight = 0.0;
    } else if (surrogate > clipped) {
      surrogate_weight = 0.0, clipped_weight = 1.0;
    }
    const bool inside = ratio_f >= low && ratio_f <= high;
    const double ratio_gradient =
        -inverse_n * advantage * (surrogate_weight + (inside ? clipped_weight : 0.0));
    log_prob_gradient[i] = ratio_gradient * ratio;  // ∂ρ/∂log π = ρ
  }
  return sums;
}

// From ∂L/∂log π: ∂L/∂μ into `mean_gradient` (n x action_size) and ∂L/∂log σ, with the
// entropy bonus's, into `log_std_gradient`. ∂log π/∂μ = z/σ and ∂log π/∂log σ = z² − 1.
void gaussian_gradients(const PpoMinibatchView& batch, const GaussianPolicy& policy,
                        const double* log_prob_gradient, double ent_coef, float* mean_gradient,
                        float* log_std_gradient) {
  const std::int64_t a_size = policy.action_size;
  for (std::int64_t j = 0; j < a_size; ++j) {
    const float inverse_std = std::exp(-policy.log_std[j]);
    double sum = ent_coef != 0.0 ? -ent_coef : 0.0;  // ∂(c_ent·(−entropy))
    for (std::int64_t i = 0; i < batch.size; ++i) {
      const float z = (batch.actions[i * a_size + j] - policy.means[i * a_size + j]) * inverse_std;
      const double g = log_prob_gradient[i];
      sum += g * (static_cast<double>(z) * z - 1.0);
      mean_gradient[i * a_size + j] = static_cast<float>(g * z * inverse_std);
    }
    log_std_gradient[j] = static_cast<float>(sum);
  }
}

// The value term: V_pred = V_old + clamp(V − V_old, ±c) (clamp passes the gradient inside
// the range, bounds included), L_v = mean((R − V_pred)²). Writes ∂(c_v·L_v)/∂V into
// `value_gradient` and returns Σ (R − V_pred)².
double value_term(const PpoMinibatchView& batch, const float* values, const PpoConfig& config,
                  float* value_gradient) {
  const bool clip_values = config.clip_range_vf > 0.0;
  const float value_clip = static_cast<float>(config.clip_range_vf);
  const double inverse_n = 1.0 / static_cast<double>(batch.size);
  double value_sum = 0.0;
  for (std::int64_t i = 0; i < batch.size; ++i) {
    float predicted = values[i];
    bool inside = true;
    if (clip_values) {
      const float old_value = batch.old_values[i];
      const float change = values[i] - old_value;
      predicted = old_value + std::clamp(change, -value_clip, value_clip);
      inside = change >= -value_clip && change <= value_clip;
    }
    const double error = static_cast<double>(batch.returns[i]) - predicted;
    value_sum += error * error;
    value_gradient[i] =
        inside ? static_cast<float>(-2.0 * config.vf_coef * inverse_n * error) : 0.0f;
  }
  return value_sum;
}

}  // namespace

void PpoGradient::check_batch(const PpoMinibatchView& batch, const ActorCritic& policy) const {
  const std::int64_t n = batch.size;
  if (n < 1 || n > max_batch_size_) {
    throw std::invalid_argument("PpoGradient: minibatch of " + std::to_string(n) +
                                " samples, expected 1 to " + std::to_string(max_batch_size_));
  }
  if (!same_shape(policy)) {
    throw std::invalid_argument("PpoGradient: the policy's shape differs from the constructor's");
  }
  check_span(batch.observations, n * networks_.actor.input_size(), "observations");
  check_span(batch.actions, n * networks_.actor.output_size(), "actions");
  check_span(batch.old_log_prob, n, "old_log_prob");
  check_span(batch.old_values, n, "old_values");
  check_span(batch.advantages, n, "advantages");
  check_span(batch.returns, n, "returns");
}

PpoLossStatistics PpoGradient::actor_part(const PpoMinibatchView& batch, const float* parameters,
                                          const PpoConfig& config, float* gradients) {
  const std::int64_t n = batch.size;
  const std::int64_t action_size = networks_.actor.output_size();
  forward(networks_.actor, actor_, parameters, batch.observations.data(), n);
  normalise_advantages(batch.advantages, config.normalize_advantage, advantages_.data());
  // Policy term: ∂L/∂μ into the actor's output gradient, ∂L/∂log σ straight into the flat
  // gradient, then back through the actor.
  const GaussianPolicy gaussian{actor_.outputs.back().data(), parameters + networks_.log_std,
                                action_size};
  const SurrogateSums sums =
      surrogate_term(batch, gaussian, advantages_.data(), config, log_prob_gradient_.data());
  gaussian_gradients(batch, gaussian, log_prob_gradient_.data(), config.ent_coef,
                     actor_.output_gradient.data(), gradients + networks_.log_std);
  backward(networks_.actor, actor_, parameters, batch.observations.data(), n, gradients);

  const double inverse_n = 1.0 / static_cast<double>(n);
  PpoLossStatistics statistics;
  statistics.policy_gradient_loss = -sums.surrogate * inverse_n;
  statistics.entropy_loss = -gaussian_entropy(
      std::span<const float>(gaussian.log_std, static_cast<std::size_t>(action_size)));
  statistics.approx_kl = sums.kl * inverse_n;
  statistics.clip_fraction = static_cast<double>(sums.clipped) * inverse_n;
  return statistics;
}

double PpoGradient::critic_part(const PpoMinibatchView& batch, const float* parameters,
                                const PpoConfig& config, float* gradients) {
  const std::int64_t n = batch.size;
  forward(networks_.critic, critic_, parameters, batch.observations.data(), n);
  // Value term, then back through the critic.
  const double value_sum =
      value_term(batch, critic_.outputs.back().data(), config, critic_.output_gradient.data());
  backward(networks_.critic, critic_, parameters, batch.observations.data(), n, gradients);
  return value_sum * (1.0 / static_cast<double>(n));
}

PpoLossStatistics PpoGradient::compute(const PpoMinibatchView& batch, ActorCritic& policy,
                                       const PpoConfig& config) {
  check_batch(batch, policy);
  const float* parameters = policy.flat_parameters().data_ptr<float>();
  float* gradients = policy.flat_gradients().data_ptr<float>();
  PpoLossStatistics statistics;
  double value_loss = 0.0;
  const auto run_actor = [&] { statistics = actor_part(batch, parameters, config, gradients); };
  const auto run_critic = [&] { value_loss = critic_part(batch, parameters, config, gradients); };
  if (companion_) {
    companion_->run_beside(run_actor, run_critic);
  } else {
    run_actor();
    run_critic();
  }
  statistics.value_loss = value_loss;
  statistics.total = statistics.policy_gradient_loss + config.vf_coef * statistics.value_loss;
  if (config.ent_coef != 0.0) statistics.total += config.ent_coef * statistics.entropy_loss;
  return statistics;
}

}  // namespace upkie_rl
