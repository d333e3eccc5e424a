#include "apps/progress_bar.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>

namespace upkie_rl::apps {

std::string with_thousands(std::int64_t value) {
  std::string digits = std::to_string(value < 0 ? -value : value);
  for (int i = static_cast<int>(digits.size()) - 3; i > 0; i -= 3) digits.insert(i, ",");
  return (value < 0 ? "-" : "") + digits;
}

std::string format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "--:--";
  const auto total = static_cast<long long>(std::llround(seconds));
  char buffer[32];
  if (total >= 3600) {
    std::snprintf(buffer, sizeof(buffer), "%lld:%02lld:%02lld", total / 3600, total / 60 % 60,
                  total % 60);
  } else {
    std::snprintf(buffer, sizeof(buffer), "%02lld:%02lld", total / 60, total % 60);
  }
  return buffer;
}

ProgressBar::ProgressBar(std::int64_t total, std::FILE* stream)
    : total_(std::max<std::int64_t>(total, 1)),
      stream_(stream),
      interactive_(isatty(fileno(stream)) != 0) {}

void ProgressBar::update(std::int64_t done, double steps_per_second, double mean_return) {
  const double fraction = std::clamp(static_cast<double>(done) / total_, 0.0, 1.0);
  const int percent = static_cast<int>(fraction * 100.0);
  if (!interactive_ && percent / 5 == last_printed_percent_ / 5) return;
  last_printed_percent_ = percent;
  constexpr int kWidth = 30;
  const int filled = static_cast<int>(fraction * kWidth);
  const std::string bar = std::string(filled, '#') + std::string(kWidth - filled, '.');
  const double eta =
      steps_per_second > 0 ? static_cast<double>(total_ - done) / steps_per_second : NAN;
  char returns[32] = "return    -";
  if (!std::isnan(mean_return)) std::snprintf(returns, sizeof(returns), "return %.1f", mean_return);
  std::fprintf(stream_, "%s[%s] %3d%% %s/%s steps | %s steps/s | ETA %s | %s%s",
               interactive_ ? "\r" : "", bar.c_str(), percent, with_thousands(done).c_str(),
               with_thousands(total_).c_str(),
               with_thousands(static_cast<std::int64_t>(steps_per_second)).c_str(),
               format_duration(eta).c_str(), returns, interactive_ ? "   " : "\n");
  std::fflush(stream_);
}

void ProgressBar::finish() {
  if (interactive_) std::fputc('\n', stream_);
  std::fflush(stream_);
}

}  // namespace upkie_rl::apps
