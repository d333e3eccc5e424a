#include "cli/progress_bar.hpp"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

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

std::string progress_line(double fraction, const std::string& steps, const std::string& total,
                          const std::string& speed, const std::string& eta,
                          const std::string& returns, int columns) {
  char percent[16];
  std::snprintf(percent, sizeof(percent), "%3d%%", static_cast<int>(fraction * 100.0));
  // Fields in the order they go when the line does not fit.
  std::vector<std::string> fields{std::string(percent) + " " + steps + "/" + total + " steps",
                                  returns, speed + " steps/s", "ETA " + eta};
  const auto joined_width = [&fields] {
    std::size_t width = 3 * (fields.size() - 1);  // " | " between fields
    for (const std::string& field : fields) width += field.size();
    return static_cast<int>(width);
  };
  constexpr int kMaxBar = 30;
  constexpr int kMinBar = 10;
  constexpr int kBarFrame = 3;  // "[", "] "
  while (fields.size() > 1 && joined_width() + kMinBar + kBarFrame > columns) fields.pop_back();
  const int bar_width = std::min(kMaxBar, columns - joined_width() - kBarFrame);
  std::string line;
  if (bar_width >= kMinBar) {
    const int filled = static_cast<int>(fraction * bar_width);
    line = "[" + std::string(filled, '#') + std::string(bar_width - filled, '.') + "] ";
  }
  for (std::size_t f = 0; f < fields.size(); ++f) line += (f ? " | " : "") + fields[f];
  if (static_cast<int>(line.size()) > columns) line.resize(std::max(columns, 0));
  return line;
}

int ProgressBar::terminal_columns() const {
  winsize size{};
  if (ioctl(fileno(stream_), TIOCGWINSZ, &size) == 0 && size.ws_col > 0) return size.ws_col;
  const char* columns = std::getenv("COLUMNS");
  const int from_environment = columns != nullptr ? std::atoi(columns) : 0;
  return from_environment > 0 ? from_environment : 80;
}

void ProgressBar::update(std::int64_t done, double steps_per_second, double mean_return) {
  const double fraction = std::clamp(static_cast<double>(done) / total_, 0.0, 1.0);
  const int percent = static_cast<int>(fraction * 100.0);
  if (!interactive_ && percent / 5 == last_printed_percent_ / 5) return;
  last_printed_percent_ = percent;
  const double eta =
      steps_per_second > 0 ? static_cast<double>(total_ - done) / steps_per_second : NAN;
  char returns[32] = "return -";
  if (!std::isnan(mean_return)) std::snprintf(returns, sizeof(returns), "return %.1f", mean_return);
  const std::string speed = with_thousands(static_cast<std::int64_t>(steps_per_second));
  if (interactive_) {
    // One column spare: a line as wide as the terminal wraps on some terminals. "\x1b[K"
    // clears what a longer previous line left.
    const std::string line =
        progress_line(fraction, with_thousands(done), with_thousands(total_), speed,
                      format_duration(eta), returns, terminal_columns() - 1);
    std::fprintf(stream_, "\r%s\x1b[K", line.c_str());
  } else {
    const std::string line = progress_line(fraction, with_thousands(done), with_thousands(total_),
                                           speed, format_duration(eta), returns, 1000);
    std::fprintf(stream_, "%s\n", line.c_str());
  }
  std::fflush(stream_);
}

void ProgressBar::finish() {
  if (interactive_) std::fputc('\n', stream_);
  std::fflush(stream_);
}

}  // namespace upkie_rl::apps
