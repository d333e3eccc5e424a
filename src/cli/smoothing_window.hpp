#pragma once
/// @file
/// The trailing mean's window of the training figures, fitted to the run.

#include <algorithm>
#include <cstddef>
#include <string>

namespace upkie_rl::apps {

/// Largest share of a run's updates a trailing-mean window may span: 1/10. A trailing mean
/// lags its data by about half its window, and a 50-update window on a 148-update run ended
/// 60 below the raw return it summarised.
inline constexpr std::size_t kUpdatesPerWindow = 10;

/// The window of a run of `updates` updates: `asked` (--window), at most updates /
/// kUpdatesPerWindow, and at least 1.
inline std::size_t fitted_window(std::size_t asked, std::size_t updates) {
  return std::max<std::size_t>(1, std::min(asked, updates / kUpdatesPerWindow));
}

/// The legend's name of the trailing mean of `window` updates, with its lag (about half the
/// window).
inline std::string smoothing_label(std::size_t window) {
  return "mean of the last " + std::to_string(window) + " updates (lags about " +
         std::to_string(window / 2) + ")";
}

}  // namespace upkie_rl::apps
