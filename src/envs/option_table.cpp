#include "envs/option_table.hpp"

#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace upkie_rl {

namespace {

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

}  // namespace

EnvOptions parse_env_options(const std::vector<std::string>& key_values) {
  EnvOptions options;
  options.reserve(key_values.size());
  for (const std::string& key_value : key_values) {
    const std::size_t equal = key_value.find('=');
    if (equal == std::string::npos || equal == 0 || equal + 1 == key_value.size()) {
      throw std::invalid_argument("malformed environment option \"" + key_value +
                                  "\": expected key=value");
    }
    options.emplace_back(key_value.substr(0, equal), key_value.substr(equal + 1));
  }
  return options;
}

std::string format_env_options(const EnvOptions& options) {
  std::string text;
  for (const auto& [key, value] : options) text += (text.empty() ? "" : " ") + key + "=" + value;
  return text;
}

void OptionTable::add_double(std::string name, double* target, double min, double max,
                             std::string help) {
  Entry entry{{std::move(name),
               OptionInfo::Type::kReal,
               std::move(help),
               format_double(*target),
               min,
               max,
               {}},
              nullptr};
  entry.parse = [target, min, max](const std::string& value, const std::string& where) {
    double parsed = 0.0;
    const char* end = value.data() + value.size();
    const auto [stop, error] = std::from_chars(value.data(), end, parsed);
    if (error != std::errc() || stop != end || !std::isfinite(parsed)) {
      throw std::invalid_argument(where + ": \"" + value + "\" is not a finite number");
    }
    if (parsed < min || parsed > max) {
      throw std::invalid_argument(where + ": " + value + " is outside [" + format_double(min) +
                                  ", " + format_double(max) + "]");
    }
    *target = parsed;
  };
  entries_.push_back(std::move(entry));
}

void OptionTable::add_int(std::string name, int* target, int min, int max, std::string help) {
  Entry entry{{std::move(name),
               OptionInfo::Type::kInteger,
               std::move(help),
               std::to_string(*target),
               static_cast<double>(min),
               static_cast<double>(max),
               {}},
              nullptr};
  entry.parse = [target, min, max](const std::string& value, const std::string& where) {
    int parsed = 0;
    const char* end = value.data() + value.size();
    const auto [stop, error] = std::from_chars(value.data(), end, parsed);
    if (error != std::errc() || stop != end) {
      throw std::invalid_argument(where + ": \"" + value + "\" is not an integer");
    }
    if (parsed < min || parsed > max) {
      throw std::invalid_argument(where + ": " + value + " is outside [" + std::to_string(min) +
                                  ", " + std::to_string(max) + "]");
    }
    *target = parsed;
  };
  entries_.push_back(std::move(entry));
}

void OptionTable::add_string(std::string name, std::string* target, std::string help) {
  Entry entry{{std::move(name), OptionInfo::Type::kText, std::move(help), *target, 0.0, 0.0, {}},
              nullptr};
  entry.parse = [target](const std::string& value, const std::string& where) {
    if (value.empty()) throw std::invalid_argument(where + ": empty value");
    *target = value;
  };
  entries_.push_back(std::move(entry));
}

void OptionTable::add_choice(std::string name, std::vector<std::string> choices,
                             std::function<void(std::size_t)> set, std::string help) {
  Entry entry{
      {std::move(name), OptionInfo::Type::kChoice,
       std::move(help) + " (" + join(choices, "|") + ")", choices.front(), 0.0, 0.0, choices},
      nullptr};
  entry.parse = [choices = std::move(choices), set = std::move(set)](const std::string& value,
                                                                     const std::string& where) {
    for (std::size_t i = 0; i < choices.size(); ++i) {
      if (value == choices[i]) {
        set(i);
        return;
      }
    }
    throw std::invalid_argument(where + ": \"" + value + "\" is not one of " + join(choices, ", "));
  };
  entries_.push_back(std::move(entry));
}

void OptionTable::mark_randomization(std::size_t first) {
  for (std::size_t i = first; i < entries_.size(); ++i) entries_[i].info.randomization = true;
}

const OptionTable::Entry* OptionTable::find(const std::string& name) const {
  for (const Entry& entry : entries_) {
    if (entry.info.name == name) return &entry;
  }
  return nullptr;
}

void OptionTable::apply(const EnvOptions& options, const std::string& context) const {
  for (const auto& [key, value] : options) {
    const Entry* entry = find(key);
    if (entry == nullptr) {
      throw std::invalid_argument(context + ": unknown option \"" + key +
                                  "\"; valid options: " + join(names(), ", "));
    }
    entry->parse(value, context + ": option " + key);
  }
}

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
