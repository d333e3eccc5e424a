#pragma once
/// @file
/// Writing one field of a CSV row (RFC 4180): the one writer of the user's text (world names,
/// controller labels, run names) into the suite's and the sweep's tables.

#include <string>
#include <string_view>

namespace upkie_rl {

/// `text` as it goes between commas: as is, or double-quoted with its quotes doubled when it
/// holds a comma, a quote or a line break ("a,b" gives "\"a,b\"", "say \"hi\"" gives
/// "\"say \"\"hi\"\"\"").
std::string csv_field(std::string_view text);

}  // namespace upkie_rl
