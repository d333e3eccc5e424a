#include "envs/records/number_row.hpp"

#include <charconv>

namespace upkie_rl {

bool parse_number_row(std::string_view line, std::span<double> values) {
  constexpr std::string_view kBlank = " \t\r";
  std::size_t start = 0;
  for (std::size_t k = 0; k < values.size(); ++k) {
    const bool last_value = k + 1 == values.size();
    const std::size_t comma = last_value ? line.size() : line.find(',', start);
    if (comma == std::string_view::npos) return false;
    std::string_view item = line.substr(start, comma - start);
    const auto first = item.find_first_not_of(kBlank);
    if (first == std::string_view::npos) return false;
    item = item.substr(first, item.find_last_not_of(kBlank) - first + 1);
    const char* end = item.data() + item.size();
    const auto [stop, error] = std::from_chars(item.data(), end, values[k]);
    if (error != std::errc() || stop != end) return false;
    start = comma + 1;
  }
  return true;
}

}  // namespace upkie_rl
