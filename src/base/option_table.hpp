#pragma once
/// @file
/// OptionTable: the one scheme in which every setting of upkie-rl is declared, once, beside
/// the struct that holds it (environment, perturbation, spine and training settings). A
/// declaration binds a name to a typed field with its range, choices and help; from it the
/// table reads key=value text, checks ranges and rules, writes the current value back as
/// text, and lists the options for `envs --options` and the Python keyword arguments.
/// Options are parsed once, when a struct is made (nothing is parsed per step).

#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "base/integer_text.hpp"
#include "base/setting_bounds.hpp"
#include "base/trim.hpp"

namespace upkie_rl {

/// key=value options, in the order given.
using OptionValues = std::vector<std::pair<std::string, std::string>>;

/// What an option accepts, for listings and typed front ends (the Python keyword arguments).
struct OptionInfo {
  /// kBoolean (true/false, yes/no, on/off, 1/0) and kIntegerList ("[64, 64]") are the
  /// training configuration's; environments spell their booleans as kChoice true|false.
  enum class Type { kReal, kInteger, kText, kChoice, kBoolean, kIntegerList };
  std::string name;
  Type type = Type::kReal;
  std::string help;
  std::string default_value;         ///< As text, as the table would read it back.
  double min = 0.0;                  ///< kReal and kInteger: lower bound.
  double max = 0.0;                  ///< kReal and kInteger: upper bound.
  bool min_excluded = false;         ///< kReal: the range is (min, max] rather than [min, max].
  std::vector<std::string> choices;  ///< kChoice: the accepted values, in declared order.
  /// Whether it sets the conditions an episode runs in (initial-state randomisation,
  /// perturbations, noise, lag) rather than the task: a trained policy carries its task
  /// options to a rollout, not these.
  bool randomization = false;
  /// What a recorded configuration (a checkpoint's env.options) that does not name the
  /// option means: its default before the option existed or its default changed; empty
  /// when a recorded configuration means the current default.
  std::string recorded_default;
};

/// An OptionInfo of the fields every option has.
inline OptionInfo option_info(std::string name, OptionInfo::Type type, std::string help,
                              std::string default_value, double min = 0.0, double max = 0.0) {
  OptionInfo info;
  info.name = std::move(name);
  info.type = type;
  info.help = std::move(help);
  info.default_value = std::move(default_value);
  info.min = min;
  info.max = max;
  return info;
}

/// A real option's name, range and help, for an option that several settings structs
/// share (the same name must mean the same range and help wherever it is declared).
struct RealOptionSpec {
  const char* name;
  double min;
  double max;
  const char* help;
};

/// A table of named options, each bound to a typed field it reads and writes.
class OptionTable {
 public:
  /// A check beyond an option's declared range (against another option, say): returns the
  /// problem ("must be at least env.num_envs"), or "" when there is none. An option's rule
  /// runs before its range check, and the table prefixes the option's name.
  using Rule = std::function<std::string()>;

  /// A real option, accepted when finite and within [min, max] (or (min, max]).
  void add_real(std::string name, double* target, double min, double max, std::string help,
                bool min_excluded = false, Rule rule = {});
  /// A real option of a shared declaration.
  void add_real(const RealOptionSpec& spec, double* target);
  /// An integer option within [min, max].
  template <class Integer>
  void add_integer(std::string name, Integer* target, Integer min, Integer max, std::string help,
                   Rule rule = {});
  /// A free-form text option (read non-empty, spaces around removed).
  void add_text(std::string name, std::string* target, std::string help, Rule rule = {});
  /// An option taking one of `choices` (spelling, value; spaces around it removed), written
  /// into `target` and written back as the first spelling of its value.
  template <class Value>
  void add_choice(std::string name, Value* target,
                  std::vector<std::pair<std::string, Value>> choices, std::string help,
                  Rule rule = {});
  /// A boolean option (true/false, yes/no, on/off, 1/0; any case).
  void add_boolean(std::string name, bool* target, std::string help);
  /// Checks a list option's value; throws std::invalid_argument naming `where`.
  using ListCheck =
      std::function<void(const std::string& where, const std::vector<std::int64_t>& value)>;
  /// A list of positive integers ("[64, 64]", "64,64"), further checked by `check`.
  void add_integer_list(std::string name, std::vector<std::int64_t>* target, std::string help,
                        ListCheck check = {});
  /// A check of several options together, run after every option's own; its problem is
  /// reported after the context alone (it names its options itself).
  void add_rule(Rule rule);

  /// Number of options so far.
  std::size_t size() const { return entries_.size(); }
  /// Marks the options from index `first` on as randomisation (OptionInfo::randomization).
  void mark_randomization(std::size_t first);
  /// Sets option `name`'s OptionInfo::recorded_default to `value` (text the table reads).
  /// @throws std::invalid_argument naming an unknown option.
  void set_recorded_default(const std::string& name, std::string value);

  /// Reads every option into its field, in order (a repeated key: the last one wins), then
  /// runs check(). Errors start with "<context>: option <name>".
  /// @throws std::invalid_argument naming an unknown key (listing the valid ones), a badly
  ///         typed or out-of-range value (saying what is expected) or a broken rule.
  void apply(const OptionValues& options, const std::string& context) const;

  /// Whether `name` is declared.
  bool contains(const std::string& name) const { return find(name) != nullptr; }
  /// Reads `text` into option `name`, without checking its range (check() does).
  /// @throws std::invalid_argument "<where>: "<text>" is not <what is expected>", or naming
  ///         an unknown option.
  void read(const std::string& name, const std::string& text, const std::string& where) const;
  /// Checks every option's rule and range, in order, then the table's rules. `where` names
  /// an option as the user wrote it (e.g. "config key 'ppo.gamma'"); `context` prefixes the
  /// table's rules.
  /// @throws std::invalid_argument "<where(name)>: <value> is outside [min, max]", or a
  ///         broken rule's problem after where(name) (or context).
  void check(const std::function<std::string(const std::string& name)>& where,
             const std::string& context) const;

  /// The current value of option `name`, as text the table reads back.
  std::string value_text(const std::string& name) const;

  /// "name: help (default ...)" lines, for listings.
  std::vector<std::string> describe() const;
  /// The names of the options, in the order added.
  std::vector<std::string> names() const;
  /// Every option's type, bounds, default and help, in the order added.
  std::vector<OptionInfo> info() const;

 private:
  struct Entry {
    OptionInfo info;
    /// Parses text into the field; false when the text is not of the option's type.
    std::function<bool(const std::string& text)> read;
    /// The field as text.
    std::function<std::string()> write;
    /// Throws (the range's message after `where`) when the field is out of range.
    std::function<void(const std::string& where, const std::string& shown)> check_range;
    Rule rule;
  };
  void add(Entry entry);
  const Entry& entry(const std::string& name) const;
  const Entry* find(const std::string& name) const;
  static void check_entry(const Entry& entry, const std::string& where, const std::string& shown);
  void check_rules(const std::string& context) const;
  std::vector<Entry> entries_;
  std::vector<Rule> rules_;
};

// Template definitions, kept beside the declarations so that any integer type works.

template <class Integer>
void OptionTable::add_integer(std::string name, Integer* target, Integer min, Integer max,
                              std::string help, Rule rule) {
  Entry entry;
  entry.info =
      option_info(std::move(name), OptionInfo::Type::kInteger, std::move(help),
                  std::to_string(*target), static_cast<double>(min), static_cast<double>(max));
  entry.read = [target](const std::string& text) {
    const std::optional<Integer> parsed = integer_from_text<Integer>(text);
    if (parsed) *target = *parsed;
    return parsed.has_value();
  };
  entry.write = [target] { return std::to_string(*target); };
  entry.check_range = [target, min, max](const std::string& where, const std::string& shown) {
    check_setting(where, *target, shown, min, max);
  };
  entry.rule = std::move(rule);
  add(std::move(entry));
}

template <class Value>
void OptionTable::add_choice(std::string name, Value* target,
                             std::vector<std::pair<std::string, Value>> choices, std::string help,
                             Rule rule) {
  Entry entry;
  std::string listed;
  for (const auto& choice : choices) {
    listed += (listed.empty() ? "" : "|") + choice.first;
    entry.info.choices.push_back(choice.first);
  }
  entry.info.name = std::move(name);
  entry.info.type = OptionInfo::Type::kChoice;
  entry.info.help = std::move(help) + " (" + listed + ")";
  entry.read = [target, choices](const std::string& text) {
    const std::string_view trimmed = trim(text);
    for (const auto& [spelling, value] : choices) {
      if (trimmed == spelling) {
        *target = value;
        return true;
      }
    }
    return false;
  };
  entry.write = [target, choices] {
    for (const auto& [spelling, value] : choices) {
      if (*target == value) return spelling;
    }
    return std::string("unknown");
  };
  entry.info.default_value = entry.write();
  entry.rule = std::move(rule);
  add(std::move(entry));
}

}  // namespace upkie_rl
