// The one splitter of separated values and the one strict number reader
// (base/split_fields.hpp, base/number_text.hpp) that the record, log, scalar-CSV, grid and
// option readers share.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "base/csv_field.hpp"
#include "base/number_text.hpp"
#include "base/split_fields.hpp"

namespace upkie_rl {
namespace {

using Fields = std::vector<std::string>;

TEST(SplitFields, KeepsEveryEmptyField) {
  EXPECT_EQ(split_fields("a,b,c"), (Fields{"a", "b", "c"}));
  EXPECT_EQ(split_fields("a,,b"), (Fields{"a", "", "b"}));
  EXPECT_EQ(split_fields("a,"), (Fields{"a", ""}));
  EXPECT_EQ(split_fields(",a"), (Fields{"", "a"}));
  EXPECT_EQ(split_fields(""), (Fields{""}));
}

TEST(CsvField, QuotesOnlyWhatNeedsItAndDoublesQuotes) {
  EXPECT_EQ(csv_field("nominal"), "nominal");
  EXPECT_EQ(csv_field(""), "");
  EXPECT_EQ(csv_field("a,b"), "\"a,b\"");
  EXPECT_EQ(csv_field("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(csv_field("two\nlines"), "\"two\nlines\"");
  // What split_fields reads back of a field without separators.
  EXPECT_EQ(split_fields(csv_field("plain") + "," + csv_field("x")), (Fields{"plain", "x"}));
}

TEST(SplitFields, TakesAnySeparator) {
  EXPECT_EQ(split_fields("0:1:0.5", ':'), (Fields{"0", "1", "0.5"}));
  EXPECT_EQ(split_fields("a,b", ':'), (Fields{"a,b"}));
}

TEST(NumberFromText, ReadsWhatShortestTextWrites) {
  for (const double value : {0.0, -1.5, 3e-4, 1e-8, 1e39, 0.1 + 0.2}) {
    const std::optional<double> read = number_from_text<double>(shortest_text(value));
    ASSERT_TRUE(read.has_value()) << value;
    EXPECT_EQ(*read, value);
  }
  EXPECT_TRUE(std::isnan(*number_from_text<double>("nan")));
  EXPECT_EQ(*number_from_text<float>(" 2.5\t"), 2.5f);
}

TEST(NumberFromText, RefusesAnythingElse) {
  for (const char* text : {"", "   ", "1.5x", "x1", "+1", "1,5", "1e999", "0x10", "1 2"}) {
    EXPECT_FALSE(number_from_text<double>(text).has_value()) << '"' << text << '"';
  }
}

}  // namespace
}  // namespace upkie_rl
