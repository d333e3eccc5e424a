#include "base/option_table.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "base/closest_name.hpp"
#include "base/integer_text.hpp"
#include "base/number_text.hpp"
#include "base/setting_bounds.hpp"

namespace upkie_rl {

namespace {

// Bounds and defaults as listings have always shown them (%g-like: "1e+09", "0.35").
std::string format_double(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

std::string join(const std::vector<std::string>& items, const char* separator) {
  std::string joined;
  for (const std::string& item : items) {
    if (!joined.empty()) joined += separator;
    joined += item;
  }
  return joined;
}

bool read_double(const std::string& raw, double* value) {
  const std::optional<double> number = number_from_text<double>(raw);
  if (number) *value = *number;
  return number.has_value();
}

bool read_boolean(const std::string& raw, bool* value) {
  std::string text(trim(raw));
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (text == "true" || text == "yes" || text == "on" || text == "1") {
    *value = true;
  } else if (text == "false" || text == "no" || text == "off" || text == "0") {
    *value = false;
  } else {
    return false;
  }
  return true;
}

bool read_integer_list(const std::string& raw, std::vector<std::int64_t>* value) {
  std::string text(trim(raw));
  if (text.size() >= 2 && text.front() == '[' && text.back() == ']') {
    text = text.substr(1, text.size() - 2);
  }
  std::vector<std::int64_t> sizes;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) {
    if (trim(item).empty()) continue;
    const std::optional<std::int64_t> size = integer_from_text<std::int64_t>(item);
    if (!size || *size <= 0) return false;
    sizes.push_back(*size);
  }
  *value = std::move(sizes);
  return true;
}

std::string format_integer_list(const std::vector<std::int64_t>& sizes) {
  std::string text = "[";
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    text += (i ? ", " : "") + std::to_string(sizes[i]);
  }
  return text + "]";
}

// What a value of `info` must look like, for "... is not <expected>".
std::string expected(const OptionInfo& info) {
  switch (info.type) {
    case OptionInfo::Type::kReal:
      return "a finite number";
    case OptionInfo::Type::kInteger:
      return "an integer";
    case OptionInfo::Type::kText:
      return "a non-empty text";
    case OptionInfo::Type::kChoice:
      return "one of " + join(info.choices, ", ");
    case OptionInfo::Type::kBoolean:
      return "true or false";
    case OptionInfo::Type::kIntegerList:
      return "a list of positive integers";
  }
  return "a value";
}

/// The refusal of an unknown option `name`: the nearest of `names` suggested, then all.
std::string unknown_option(const std::string& name, const std::vector<std::string>& names) {
  return "unknown option \"" + name + "\"" + did_you_mean(name, names) +
         "; valid options: " + join(names, ", ");
}

}  // namespace

void OptionTable::add(Entry entry) {
  // A name declared twice would read into one field and leave the other at its default.
  if (find(entry.info.name) != nullptr) {
    throw std::logic_error("option \"" + entry.info.name + "\" declared twice");
  }
  entries_.push_back(std::move(entry));
}

void OptionTable::add_real(std::string name, double* target, double min, double max,
                           std::string help, bool min_excluded, Rule rule) {
  Entry entry;
  entry.info = option_info(std::move(name), OptionInfo::Type::kReal, std::move(help),
                           format_double(*target), min, max);
  entry.info.min_excluded = min_excluded;
  entry.read = [target](const std::string& text) { return read_double(text, target); };
  entry.write = [target] { return shortest_text(*target); };
  entry.check_range = [target, min, max, min_excluded](const std::string& where,
                                                       const std::string& shown) {
    check_setting(where, *target, shown, min, max,
                  min_excluded ? LowerBound::kExcluded : LowerBound::kIncluded);
  };
  entry.rule = std::move(rule);
  add(std::move(entry));
}

void OptionTable::add_real(const RealOptionSpec& spec, double* target) {
  add_real(spec.name, target, spec.min, spec.max, spec.help);
}

void OptionTable::add_text(std::string name, std::string* target, std::string help, Rule rule) {
  Entry entry;
  entry.info = option_info(std::move(name), OptionInfo::Type::kText, std::move(help), *target);
  entry.read = [target](const std::string& text) {
    const std::string_view trimmed = trim(text);
    if (trimmed.empty()) return false;
    *target = std::string(trimmed);
    return true;
  };
  entry.write = [target] { return *target; };
  entry.rule = std::move(rule);
  add(std::move(entry));
}

void OptionTable::add_boolean(std::string name, bool* target, std::string help) {
  Entry entry;
  entry.info = option_info(std::move(name), OptionInfo::Type::kBoolean, std::move(help),
                           *target ? "true" : "false");
  entry.read = [target](const std::string& text) { return read_boolean(text, target); };
  entry.write = [target] { return std::string(*target ? "true" : "false"); };
  add(std::move(entry));
}

void OptionTable::add_integer_list(std::string name, std::vector<std::int64_t>* target,
                                   std::string help, ListCheck check) {
  Entry entry;
  entry.info = option_info(std::move(name), OptionInfo::Type::kIntegerList, std::move(help),
                           format_integer_list(*target));
  entry.read = [target](const std::string& text) { return read_integer_list(text, target); };
  entry.write = [target] { return format_integer_list(*target); };
  if (check) {
    entry.check_range = [target, check](const std::string& where, const std::string&) {
      check(where, *target);
    };
  }
  add(std::move(entry));
}

void OptionTable::add_rule(Rule rule) { rules_.push_back(std::move(rule)); }

void OptionTable::mark_randomization(std::size_t first) {
  for (std::size_t i = first; i < entries_.size(); ++i) entries_[i].info.randomization = true;
}

void OptionTable::set_recorded_default(const std::string& name, std::string value) {
  const_cast<Entry&>(entry(name)).info.recorded_default = std::move(value);  // NOLINT: ours
}

const OptionTable::Entry* OptionTable::find(const std::string& name) const {
  for (const Entry& entry : entries_) {
    if (entry.info.name == name) return &entry;
  }
  return nullptr;
}

const OptionTable::Entry& OptionTable::entry(const std::string& name) const {
  const Entry* found = find(name);
  if (found == nullptr) {
    throw std::invalid_argument(unknown_option(name, names()));
  }
  return *found;
}

void OptionTable::read(const std::string& name, const std::string& text,
                       const std::string& where) const {
  const Entry& found = entry(name);
  if (found.read(text)) return;
  if (found.info.type == OptionInfo::Type::kText) {
    throw std::invalid_argument(where + ": empty value");
  }
  throw std::invalid_argument(where + ": \"" + text + "\" is not " + expected(found.info));
}

void OptionTable::check_entry(const Entry& entry, const std::string& where,
                              const std::string& shown) {
  if (entry.rule) {
    const std::string problem = entry.rule();
    if (!problem.empty()) throw std::invalid_argument(where + ": " + problem);
  }
  if (entry.check_range) entry.check_range(where, shown);
}

void OptionTable::check_rules(const std::string& context) const {
  for (const Rule& rule : rules_) {
    const std::string problem = rule();
    if (!problem.empty()) throw std::invalid_argument(context + ": " + problem);
  }
}

void OptionTable::apply(const OptionValues& options, const std::string& context) const {
  for (const auto& [key, value] : options) {
    if (find(key) == nullptr) {
      throw std::invalid_argument(context + ": " + unknown_option(key, names()));
    }
    const std::string where = context + ": option " + key;
    read(key, value, where);
    // Checked at once, so that the message shows the value as the user wrote it.
    check_entry(entry(key), where, value);
  }
  check_rules(context);
}

void OptionTable::check(const std::function<std::string(const std::string& name)>& where,
                        const std::string& context) const {
  for (const Entry& entry : entries_) check_entry(entry, where(entry.info.name), "");
  check_rules(context);
}

std::string OptionTable::value_text(const std::string& name) const { return entry(name).write(); }

std::vector<std::string> OptionTable::describe() const {
  std::vector<std::string> lines;
  lines.reserve(entries_.size());
  for (const Entry& entry : entries_) {
    const OptionInfo& info = entry.info;
    lines.push_back(info.name + ": " + info.help + " (default " + info.default_value + ")");
  }
  return lines;
}

std::vector<std::string> OptionTable::names() const {
  std::vector<std::string> list;
  list.reserve(entries_.size());
  for (const Entry& entry : entries_) list.push_back(entry.info.name);
  return list;
}

std::vector<OptionInfo> OptionTable::info() const {
  std::vector<OptionInfo> list;
  list.reserve(entries_.size());
  for (const Entry& entry : entries_) list.push_back(entry.info);
  return list;
}

}  // namespace upkie_rl
