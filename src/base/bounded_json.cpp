#include "base/bounded_json.hpp"

#include <stdexcept>

namespace upkie_rl {

std::size_t json_nesting_depth(std::string_view text) {
  std::size_t depth = 0;
  std::size_t deepest = 0;
  bool in_string = false;
  bool escaped = false;
  for (const char c : text) {
    if (in_string) {
      if (escaped) {
        escaped = false;
      } else if (c == '\\') {
        escaped = true;
      } else if (c == '"') {
        in_string = false;
      }
      continue;
    }
    if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return deepest;
}

nlohmann::json parse_bounded_json(std::string_view text, const std::string& where,
                                  std::size_t max_depth) {
  const std::size_t depth = json_nesting_depth(text);
  if (depth > max_depth) {
    throw std::invalid_argument(where + ": JSON nested " + std::to_string(depth) +
                                " levels deep, more than the limit " + std::to_string(max_depth));
  }
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& error) {
    throw std::invalid_argument(where + ": malformed JSON: " + error.what());
  }
}

}  // namespace upkie_rl
