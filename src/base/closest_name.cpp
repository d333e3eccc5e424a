#include "base/closest_name.hpp"

#include <algorithm>
#include <cctype>
#include <limits>

namespace upkie_rl {

namespace {

bool same_letter(char a, char b) {
  return std::tolower(static_cast<unsigned char>(a)) == std::tolower(static_cast<unsigned char>(b));
}

}  // namespace

std::size_t edit_distance(std::string_view a, std::string_view b) {
  // Optimal string alignment: three rows of the dynamic programme (the swap looks two back).
  std::vector<std::size_t> before(b.size() + 1), previous(b.size() + 1), current(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) previous[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    current[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t substitution = same_letter(a[i - 1], b[j - 1]) ? 0 : 1;
      current[j] = std::min({previous[j] + 1, current[j - 1] + 1, previous[j - 1] + substitution});
      if (i > 1 && j > 1 && same_letter(a[i - 1], b[j - 2]) && same_letter(a[i - 2], b[j - 1])) {
        current[j] = std::min(current[j], before[j - 2] + 1);
      }
    }
    std::swap(before, previous);
    std::swap(previous, current);
  }
  return previous[b.size()];
}

std::optional<std::string> closest_name(std::string_view wrong,
                                        const std::vector<std::string>& names) {
  if (wrong.empty()) return std::nullopt;
  // Near enough: a typo or two, more in a long name, but never a rewrite of a short one.
  const std::size_t limit = std::min(std::max<std::size_t>(2, wrong.size() / 4), wrong.size() - 1);
  std::size_t best = std::numeric_limits<std::size_t>::max();
  const std::string* found = nullptr;
  for (const std::string& name : names) {
    const std::size_t distance = edit_distance(wrong, name);
    if (distance < best) {
      best = distance;
      found = &name;
    }
  }
  if (found == nullptr || best > limit) return std::nullopt;
  return *found;
}

std::string did_you_mean(std::string_view wrong, const std::vector<std::string>& names) {
  const std::optional<std::string> name = closest_name(wrong, names);
  return name ? " (did you mean \"" + *name + "\"?)" : "";
}

}  // namespace upkie_rl
