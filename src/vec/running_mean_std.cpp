#include "vec/running_mean_std.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "vec/normalization_state.hpp"

namespace upkie_rl {

namespace key = normalization_state;

RunningMeanStd::RunningMeanStd(std::size_t size, double initial_count)
    : mean_(size, 0.0),
      var_(size, 1.0),
      count_(initial_count),
      batch_mean_(size, 0.0),
      batch_var_(size, 0.0) {
  if (size == 0) throw std::invalid_argument("RunningMeanStd: size must be positive");
}

template <typename T>
void RunningMeanStd::update_rows(std::span<const T> batch) {
  const std::size_t n = size();
  if (batch.empty() || batch.size() % n != 0) {
    throw std::invalid_argument("RunningMeanStd: batch of " + std::to_string(batch.size()) +
                                " values is not a whole number of rows of " + std::to_string(n));
  }
  const std::size_t rows = batch.size() / n;
  std::fill(batch_mean_.begin(), batch_mean_.end(), 0.0);
  std::fill(batch_var_.begin(), batch_var_.end(), 0.0);
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t j = 0; j < n; ++j) batch_mean_[j] += batch[r * n + j];
  }
  for (std::size_t j = 0; j < n; ++j) batch_mean_[j] /= static_cast<double>(rows);
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t j = 0; j < n; ++j) {
      const double d = batch[r * n + j] - batch_mean_[j];
      batch_var_[j] += d * d;
    }
  }
  for (std::size_t j = 0; j < n; ++j) batch_var_[j] /= static_cast<double>(rows);
  update_from_moments(batch_mean_, batch_var_, static_cast<double>(rows));
}

void RunningMeanStd::update(std::span<const float> batch) { update_rows(batch); }
void RunningMeanStd::update(std::span<const double> batch) { update_rows(batch); }

void RunningMeanStd::update_from_moments(std::span<const double> batch_mean,
                                         std::span<const double> batch_var, double batch_count) {
  if (batch_mean.size() != size() || batch_var.size() != size()) {
    throw std::invalid_argument("RunningMeanStd: moments of the wrong size");
  }
  const double total = count_ + batch_count;
  for (std::size_t j = 0; j < size(); ++j) {
    const double delta = batch_mean[j] - mean_[j];
    const double m2 = var_[j] * count_ + batch_var[j] * batch_count +
                      delta * delta * count_ * batch_count / total;
    mean_[j] += delta * batch_count / total;
    var_[j] = m2 / total;
  }
  count_ = total;
}

nlohmann::json RunningMeanStd::to_json() const {
  return {{key::kMean, mean_}, {key::kVar, var_}, {key::kCount, count_}};
}

void RunningMeanStd::from_json(const nlohmann::json& json, const std::string& name) {
  if (!json.is_object()) throw std::invalid_argument(name + " must be an object");
  auto read_vector = [&](const char* entry) {
    if (!json.contains(entry)) throw std::invalid_argument("missing key " + name + "." + entry);
    const nlohmann::json& value = json.at(entry);
    if (!value.is_array() || value.size() != size()) {
      throw std::invalid_argument(name + "." + entry + " must be an array of " +
                                  std::to_string(size()) + " numbers");
    }
    std::vector<double> out;
    out.reserve(size());
    for (const auto& item : value) {
      if (!item.is_number())
        throw std::invalid_argument(name + "." + entry + " holds a non-number");
      out.push_back(item.get<double>());
    }
    return out;
  };
  std::vector<double> mean = read_vector(key::kMean);
  std::vector<double> var = read_vector(key::kVar);
  const std::string where = name + ".";
  if (!json.contains(key::kCount))
    throw std::invalid_argument("missing key " + where + key::kCount);
  const nlohmann::json& count = json.at(key::kCount);
  if (!count.is_number() || !(count.get<double>() > 0.0) || !std::isfinite(count.get<double>())) {
    throw std::invalid_argument(where + key::kCount + " must be a finite positive number");
  }
  for (double m : mean) {
    if (!std::isfinite(m))
      throw std::invalid_argument(where + key::kMean + " must hold finite numbers");
  }
  for (double v : var) {
    if (!(v >= 0.0) || !std::isfinite(v)) {
      throw std::invalid_argument(where + key::kVar + " must hold finite non-negative numbers");
    }
  }
  mean_ = std::move(mean);
  var_ = std::move(var);
  count_ = count.get<double>();
}

void RunningMeanStd::merge_across_processes(
    RunningMeanStd& at_last_merge,
    const std::function<void(std::span<double>)>& sum_over_processes) {
  const std::size_t n = size();
  // What this process added since the last merge, recovered from the parallel-merge
  // formulas: count, then per component the sums of x and of x squared about zero.
  const double added = count_ - at_last_merge.count_;
  std::vector<double> sums(1 + 2 * n, 0.0);
  sums[0] = added;
  if (added > 0.0) {
    for (std::size_t i = 0; i < n; ++i) {
      const double mean_before = at_last_merge.mean_[i];
      const double added_mean = (mean_[i] * count_ - mean_before * at_last_merge.count_) / added;
      const double delta = added_mean - mean_before;
      const double added_m2 = var_[i] * count_ - at_last_merge.var_[i] * at_last_merge.count_ -
                              delta * delta * at_last_merge.count_ * added / count_;
      sums[1 + i] = added * added_mean;
      sums[1 + n + i] = added_m2 + added * added_mean * added_mean;
    }
  }
  sum_over_processes(sums);
  const double total = sums[0];
  if (total > 0.0) {
    std::vector<double> batch_mean(n), batch_var(n);
    for (std::size_t i = 0; i < n; ++i) {
      batch_mean[i] = sums[1 + i] / total;
      batch_var[i] = std::max(0.0, sums[1 + n + i] / total - batch_mean[i] * batch_mean[i]);
    }
    at_last_merge.update_from_moments(batch_mean, batch_var, total);
  }
  mean_ = at_last_merge.mean_;
  var_ = at_last_merge.var_;
  count_ = at_last_merge.count_;
}

}  // namespace upkie_rl
