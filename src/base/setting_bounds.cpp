#include "base/setting_bounds.hpp"

#include <unistd.h>

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "base/number_text.hpp"

namespace upkie_rl {

namespace {

std::string format_bytes(double bytes) {
  std::ostringstream out;
  out.precision(3);
  out << bytes / 1e9 << " GB";
  return out.str();
}

}  // namespace

void check_setting(const std::string& name, double value, double min, double max,
                   LowerBound lower) {
  check_setting(name, value, "", min, max, lower);
}

void check_setting(const std::string& name, double value, const std::string& shown, double min,
                   double max, LowerBound lower) {
  const bool below = lower == LowerBound::kIncluded ? value < min : value <= min;
  if (std::isfinite(value) && !below && value <= max) return;
  // Appended to a string made first: "(" + std::string makes GCC 12 warn (-Wrestrict, a
  // false positive of its inlined insert).
  std::string range(lower == LowerBound::kIncluded ? "[" : "(");
  range += shortest_text(min) + ", " + shortest_text(max) + "]";
  const std::string text = shown.empty() ? shortest_text(value) : shown;
  if (!std::isfinite(value)) {
    throw std::invalid_argument(name + ": " + text + " is not a finite number; expected one in " +
                                range);
  }
  throw std::invalid_argument(name + ": " + text + " is outside " + range);
}

std::uint64_t physical_memory_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long page_size = sysconf(_SC_PAGESIZE);
  if (pages <= 0 || page_size <= 0) return 0;
  return static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page_size);
}

void check_allocation(const std::string& name, const std::string& value, double bytes,
                      const std::string& what) {
  const double memory = static_cast<double>(physical_memory_bytes());
  if (memory <= 0 || bytes <= memory / 2) return;
  throw std::invalid_argument(name + ": " + value + " would make " + what + " need " +
                              format_bytes(bytes) + ", more than half of this machine's " +
                              format_bytes(memory) + " of memory");
}

}  // namespace upkie_rl
