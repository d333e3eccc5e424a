#include "cli/fall_statistics.hpp"

#include <algorithm>
#include <boost/math/distributions/binomial.hpp>
#include <boost/math/distributions/hypergeometric.hpp>
#include <limits>

namespace upkie_rl::apps {

double fall_rate_upper_bound(int falls, int episodes, double confidence) {
  if (episodes <= 0 || falls < 0 || falls > episodes) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  if (falls == episodes) return 1.0;
  using Binomial = boost::math::binomial_distribution<double>;
  return Binomial::find_upper_bound_on_p(episodes, falls, 1.0 - confidence);
}

double more_falls_p_value(int a_falls, int a_episodes, int b_falls, int b_episodes) {
  if (a_episodes <= 0 || b_episodes <= 0 || a_falls < 0 || b_falls < 0 || a_falls > a_episodes ||
      b_falls > b_episodes) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  // a takes at least this many of the falls in any draw (b has too few episodes for more).
  const int fewest_possible = std::max(0, a_falls + b_falls - b_episodes);
  if (a_falls <= fewest_possible) return 1.0;
  // a's falls among all the falls, drawn without replacement from both runs' episodes.
  const boost::math::hypergeometric_distribution<double> a_share(
      static_cast<unsigned>(a_falls + b_falls), static_cast<unsigned>(a_episodes),
      static_cast<unsigned>(a_episodes + b_episodes));
  return boost::math::cdf(boost::math::complement(a_share, static_cast<unsigned>(a_falls - 1)));
}

}  // namespace upkie_rl::apps
