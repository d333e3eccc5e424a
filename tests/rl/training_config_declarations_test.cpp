// TrainingConfig declares each key once (TrainingConfig::declare_options); reading YAML,
// --set overrides, validation and writing all come from that declaration. A key declared
// for one direction only fails here.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "rl/runs/training_config.hpp"

namespace upkie_rl {
namespace {

std::string exact(double value) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.17g", value);
  return text;
}

// A valid value of `option` other than its default.
std::string changed_value(const OptionInfo& option) {
  switch (option.type) {
    case OptionInfo::Type::kReal: {
      const double base = std::stod(option.default_value);
      return exact(base != 0.0 ? base / 2 : option.max / 2);
    }
    case OptionInfo::Type::kInteger: {
      // One below when the default is the largest value (ppo.update_threads: 2 of [1, 2]).
      const long long base = std::stoll(option.default_value);
      return std::to_string(static_cast<double>(base) + 1 <= option.max ? base + 1 : base - 1);
    }
    case OptionInfo::Type::kBoolean:
      return option.default_value == "true" ? "false" : "true";
    case OptionInfo::Type::kChoice:
      // The last: a choice may list other spellings of its values after them
      // (policy.activation: relu, ..., selu, then ReLU, ..., SELU).
      return option
          .choices[option.choices.back() == option.default_value ? 0 : option.choices.size() - 1];
    case OptionInfo::Type::kIntegerList:
      return "[3, 5]";
    case OptionInfo::Type::kText:
      return "Upkie-Mock-Servos";
  }
  return "";
}

TEST(TrainingConfigDeclarations, EveryKeyRoundTripsThroughYaml) {
  TrainingConfig written;
  OptionTable declared;
  written.declare_options(declared);
  const std::vector<OptionInfo> keys = declared.info();
  ASSERT_GE(keys.size(), 30u);
  for (const OptionInfo& key : keys) {
    apply_overrides(written, {key.name + "=" + changed_value(key)});
    EXPECT_NE(declared.value_text(key.name), key.default_value) << key.name;
  }
  written.env_options = {{"frequency", "100"}};
  ASSERT_NO_THROW(written.validate());
  const std::string yaml = to_yaml(written);
  TrainingConfig read = parse_training_config(yaml);
  OptionTable read_table;
  read.declare_options(read_table);
  for (const OptionInfo& key : keys) {
    const std::string leaf = key.name.substr(key.name.find('.') + 1);
    EXPECT_NE(yaml.find(leaf + ": "), std::string::npos) << key.name << " not written";
    EXPECT_EQ(read_table.value_text(key.name), declared.value_text(key.name)) << key.name;
  }
  EXPECT_EQ(read.env_options, written.env_options);
  EXPECT_EQ(to_yaml(read), yaml);
}

TEST(TrainingConfigDeclarations, ValidateChecksEveryDeclaredRange) {
  TrainingConfig config;
  OptionTable declared;
  config.declare_options(declared);
  for (const OptionInfo& key : declared.info()) {
    if (key.type != OptionInfo::Type::kReal && key.type != OptionInfo::Type::kInteger) continue;
    if (key.max >= 9e18) continue;  // no upper bound (seed, ppo.batch_size)
    TrainingConfig broken;
    const double above = key.max * 2 + 1;
    const std::string text = key.type == OptionInfo::Type::kReal
                                 ? exact(above)
                                 : std::to_string(static_cast<long long>(above));
    apply_overrides(broken, {key.name + "=" + text});
    try {
      broken.validate();
      ADD_FAILURE() << key.name << "=" << text << " was accepted";
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find("'" + key.name + "'"), std::string::npos)
          << error.what();
    }
  }
}

}  // namespace
}  // namespace upkie_rl
