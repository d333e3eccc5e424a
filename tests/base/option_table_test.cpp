// OptionTable: one declaration per option gives reading, range checks, writing and listing.

#include "base/option_table.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>
#include "common/error_message.hpp"

namespace upkie_rl {
namespace {

enum class Colour { kRed, kBlue };

struct Settings {
  double gain = 0.5;
  int steps = 3;
  std::int64_t budget = 7;
  std::string name = "robot";
  Colour colour = Colour::kBlue;
  bool verbose = false;
  std::vector<std::int64_t> sizes{4, 4};

  OptionTable table() {
    OptionTable table;
    table.add_real("gain", &gain, 0.0, 1.0, "a gain", true);
    table.add_integer("steps", &steps, 0, 10, "a count");
    table.add_integer<std::int64_t>("budget", &budget, 1, 100, "a budget", [this] {
      return budget < steps ? std::string("must be at least steps") : std::string();
    });
    table.add_text("name", &name, "a name");
    table.add_choice("colour", &colour, {{"red", Colour::kRed}, {"blue", Colour::kBlue}},
                     "a colour");
    table.add_boolean("verbose", &verbose, "talk");
    table.add_integer_list("sizes", &sizes, "widths");
    return table;
  }
};

using testing::error_message;

TEST(OptionTable, ApplyReadsEveryTypeAndChecksRangesAtOnce) {
  Settings settings;
  const OptionTable table = settings.table();
  table.apply({{"gain", "0.25"},
               {"steps", "9"},
               {"budget", "12"},
               {"name", "upkie"},
               {"colour", "red"},
               {"verbose", "yes"},
               {"sizes", "[8, 16]"}},
              "Test");
  EXPECT_EQ(settings.gain, 0.25);
  EXPECT_EQ(settings.steps, 9);
  EXPECT_EQ(settings.budget, 12);
  EXPECT_EQ(settings.name, "upkie");
  EXPECT_EQ(settings.colour, Colour::kRed);
  EXPECT_TRUE(settings.verbose);
  EXPECT_EQ(settings.sizes, (std::vector<std::int64_t>{8, 16}));
}

TEST(OptionTable, ErrorsNameTheOptionTheValueAndTheRange) {
  Settings settings;
  const OptionTable table = settings.table();
  EXPECT_EQ(error_message([&] {
              table.apply({{"gain", "0"}}, "Test");
            }),
            "Test: option gain: 0 is outside (0, 1]");
  EXPECT_EQ(error_message([&] {
              table.apply({{"gain", "-1.0"}}, "Test");
            }),
            "Test: option gain: -1.0 is outside (0, 1]");
  EXPECT_EQ(error_message([&] {
              table.apply({{"steps", "11"}}, "Test");
            }),
            "Test: option steps: 11 is outside [0, 10]");
  EXPECT_EQ(error_message([&] {
              table.apply({{"steps", "two"}}, "Test");
            }),
            "Test: option steps: \"two\" is not an integer");
  EXPECT_EQ(error_message([&] {
              table.apply({{"colour", "green"}}, "Test");
            }),
            "Test: option colour: \"green\" is not one of red, blue");
  EXPECT_EQ(error_message([&] {
              table.apply({{"gain", "nan"}}, "Test");
            }),
            "Test: option gain: nan is not a finite number; expected one in (0, 1]");
  EXPECT_EQ(error_message([&] {
              table.apply({{"budget", "2"}}, "Test");
            }),
            "Test: option budget: must be at least steps");
  EXPECT_EQ(error_message([&] {
              table.apply({{"speed", "1"}}, "Test");
            }),
            "Test: unknown option \"speed\"; valid options: gain, steps, budget, name, colour, "
            "verbose, sizes");
}

TEST(OptionTable, CheckNamesTheOptionAsTheCallerWritesIt) {
  Settings settings;
  const OptionTable table = settings.table();
  settings.steps = 20;  // set directly, as code does, then checked
  EXPECT_EQ(error_message([&] {
              table.check([](const std::string& n) { return "key '" + n + "'"; }, "Test");
            }),
            "key 'steps': 20 is outside [0, 10]");
}

TEST(OptionTable, EveryValueReadsBackAsItWasWritten) {
  Settings written;
  written.gain = 0.1 + 0.2;  // needs 17 digits
  written.steps = 4;
  written.budget = 99;
  written.name = "x y";
  written.colour = Colour::kRed;
  written.verbose = true;
  written.sizes = {1, 2, 3};
  const OptionTable source = written.table();
  Settings read;
  const OptionTable target = read.table();
  for (const std::string& name : source.names()) {
    target.read(name, source.value_text(name), name);
    EXPECT_EQ(target.value_text(name), source.value_text(name)) << name;
  }
  EXPECT_EQ(read.gain, written.gain);
  EXPECT_EQ(read.sizes, written.sizes);
  EXPECT_EQ(read.colour, written.colour);
}

TEST(OptionTable, InfoListsDefaultsBoundsAndChoices) {
  Settings settings;
  const std::vector<OptionInfo> info = settings.table().info();
  ASSERT_EQ(info.size(), 7u);
  EXPECT_EQ(info[0].default_value, "0.5");
  EXPECT_TRUE(info[0].min_excluded);
  EXPECT_EQ(info[1].max, 10.0);
  EXPECT_EQ(info[4].default_value, "blue");
  EXPECT_EQ(info[4].choices, (std::vector<std::string>{"red", "blue"}));
  EXPECT_EQ(info[4].help, "a colour (red|blue)");
  EXPECT_EQ(info[5].type, OptionInfo::Type::kBoolean);
  EXPECT_EQ(info[6].default_value, "[4, 4]");
}

TEST(OptionTable, ANameDeclaredTwiceIsRefused) {
  double first = 0.0;
  double second = 0.0;
  OptionTable table;
  table.add_real("gain", &first, 0.0, 1.0, "one");
  EXPECT_THROW(table.add_real("gain", &second, 0.0, 1.0, "two"), std::logic_error);
}

TEST(OptionTable, TableRulesRunAfterEveryOption) {
  double low = 0.0;
  double high = 1.0;
  OptionTable table;
  table.add_real("low", &low, 0.0, 10.0, "low");
  table.add_real("high", &high, 0.0, 10.0, "high");
  table.add_rule([&] { return low > high ? std::string("low is above high") : std::string(); });
  // Each value alone would break the rule against the other's old value; together they pass.
  EXPECT_NO_THROW(table.apply({{"low", "5"}, {"high", "6"}}, "Test"));
  EXPECT_EQ(error_message([&] { table.apply({{"low", "7"}}, "Test"); }), "Test: low is above high");
}

}  // namespace
}  // namespace upkie_rl
