#pragma once
/// @file
/// RunningMeanStd: running mean and variance of vectors (SB3's RunningMeanStd, float64).

#include <functional>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

namespace upkie_rl {

/// Mean and (population) variance per component of every vector seen so far, merged batch
/// by batch with the parallel algorithm (Chan et al.). Starts at mean 0, var 1, count
/// `initial_count` (1e-4, as SB3).
class RunningMeanStd {
 public:
  explicit RunningMeanStd(std::size_t size = 1, double initial_count = 1e-4);

  std::size_t size() const { return mean_.size(); }
  const std::vector<double>& mean() const { return mean_; }
  const std::vector<double>& var() const { return var_; }
  double count() const { return count_; }

  /// Merges a batch of rows (batch.size() a multiple of size(), at least one row).
  /// Allocation-free. @throws std::invalid_argument on a bad size.
  void update(std::span<const float> batch);
  void update(std::span<const double> batch);

  /// Merges a batch given by its moments (var is the population variance).
  void update_from_moments(std::span<const double> batch_mean, std::span<const double> batch_var,
                           double batch_count);

  /// Makes this the statistics of every process of a data-parallel run. `at_last_merge` is a
  /// copy of this object after the previous merge (or the start); since then each process
  /// updated its own copy with its own batches. The moments each process added are summed
  /// over the processes by `sum_over_processes` (in place, the same length everywhere) and
  /// merged into `at_last_merge`; the result becomes both this object and the new
  /// `at_last_merge`, identical on every process.
  void merge_across_processes(RunningMeanStd& at_last_merge,
                              const std::function<void(std::span<double>)>& sum_over_processes);

  /// {"mean": [...], "var": [...], "count": c} (keys: vec/normalization_state.hpp).
  nlohmann::json to_json() const;
  /// Reads to_json()'s output.
  /// @throws std::invalid_argument naming `name`.field on a missing key, a wrong type or a
  ///         size different from size().
  void from_json(const nlohmann::json& json, const std::string& name);

 private:
  template <typename T>
  void update_rows(std::span<const T> batch);

  std::vector<double> mean_;
  std::vector<double> var_;
  double count_;
  std::vector<double> batch_mean_;  // Scratch buffers, sized once.
  std::vector<double> batch_var_;
};

}  // namespace upkie_rl
