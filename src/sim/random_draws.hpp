#pragma once
/// @file
/// Random draws from a 64-bit Mersenne Twister that give the same numbers with every
/// standard library (the <random> distributions are implementation-defined).

#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>

namespace upkie_rl {

/// A uniform draw in [0, 1) from 53 random bits.
inline double uniform_unit(std::mt19937_64& generator) {
  return static_cast<double>(generator() >> 11) * 0x1.0p-53;
}

/// A uniform draw in [-half_width, half_width].
inline double uniform_symmetric(std::mt19937_64& generator, double half_width) {
  return half_width * (2.0 * uniform_unit(generator) - 1.0);
}

/// A uniform draw in [low, high].
inline double uniform_between(std::mt19937_64& generator, double low, double high) {
  return low + (high - low) * uniform_unit(generator);
}

/// A uniform integer draw in {low, ..., high} (low <= high), from one uniform_unit draw.
inline int uniform_integer(std::mt19937_64& generator, int low, int high) {
  const double span = static_cast<double>(high) - static_cast<double>(low) + 1.0;
  const int offset = static_cast<int>(std::floor(span * uniform_unit(generator)));
  return offset > high - low ? high : low + offset;  // the guard covers rounding at the top
}

/// A standard normal draw (Box-Muller; two uniform draws per call, the second normal of
/// the pair discarded so that the count of draws never depends on history).
inline double standard_normal(std::mt19937_64& generator) {
  const double u1 = 1.0 - uniform_unit(generator);  // in (0, 1]: log is finite
  const double u2 = uniform_unit(generator);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

/// A seed for a sub-generator derived from a parent seed and a stream number (splitmix64),
/// so that streams drawn from one seed are independent of each other.
inline std::uint64_t derive_seed(std::uint64_t seed, std::uint64_t stream) {
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ULL * (stream + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

}  // namespace upkie_rl
