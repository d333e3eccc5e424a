#include "base/split_fields.hpp"

namespace upkie_rl {

std::vector<std::string> split_fields(std::string_view line, char separator) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t found = line.find(separator, start);
    fields.emplace_back(
        line.substr(start, found == std::string_view::npos ? found : found - start));
    if (found == std::string_view::npos) return fields;
    start = found + 1;
  }
}

}  // namespace upkie_rl
