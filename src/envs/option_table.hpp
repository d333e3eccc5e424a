#pragma once
/// @file
/// OptionTable: turns key=value environment options into typed fields, once, at
/// construction (nothing is parsed per step).

#include <functional>
#include <string>
#include <vector>

#include "envs/env_options.hpp"

namespace upkie_rl {

/// What an option accepts, for listings and typed front ends (the Python keyword arguments).
struct OptionInfo {
  enum class Type { kReal, kInteger, kText, kChoice };
  std::string name;
  Type type = Type::kReal;
  std::string help;
  std::string default_value;         ///< As text, as `apply` would accept it.
  double min = 0.0;                  ///< kReal and kInteger: lower bound.
  double max = 0.0;                  ///< kReal and kInteger: upper bound.
  std::vector<std::string> choices;  ///< kChoice: the accepted values, default first.
  /// Whether it sets the conditions an episode runs in (initial-state randomisation,
  /// perturbations, noise, lag) rather than the task: a trained policy carries its task
  /// options to a rollout, not these.
  bool randomization = false;
};

/// A table of named options, each bound to a typed field it writes.
class OptionTable {
 public:
  /// A real-valued option, accepted when finite and within [min, max].
  void add_double(std::string name, double* target, double min, double max, std::string help);
  /// An integer option within [min, max].
  void add_int(std::string name, int* target, int min, int max, std::string help);
  /// A free-form text option (non-empty).
  void add_string(std::string name, std::string* target, std::string help);
  /// An option taking one of `choices`, the first being the default; `set` receives the
  /// index of the chosen one.
  void add_choice(std::string name, std::vector<std::string> choices,
                  std::function<void(std::size_t)> set, std::string help);

  /// Number of options so far.
  std::size_t size() const { return entries_.size(); }
  /// Marks the options from index `first` on as randomisation (OptionInfo::randomization).
  void mark_randomization(std::size_t first);

  /// Writes every option into its field, in order (a repeated key: the last one wins).
  /// @throws std::invalid_argument naming an unknown key (listing the valid ones) or a
  ///         badly typed or out-of-range value (saying what is expected).
  void apply(const EnvOptions& options, const std::string& context) const;

  /// "name: help (default ...)" lines, for listings.
  std::vector<std::string> describe() const;

  /// The names of the options, in the order added.
  std::vector<std::string> names() const;

  /// Every option's type, bounds, default and help, in the order added.
  std::vector<OptionInfo> info() const;

 private:
  struct Entry {
    OptionInfo info;
    std::function<void(const std::string& value, const std::string& where)> parse;
  };
  const Entry* find(const std::string& name) const;
  std::vector<Entry> entries_;
};

}  // namespace upkie_rl
