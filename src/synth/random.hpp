#pragma once
// Random numbers that are the same on every standard library: std::mt19937 is specified exactly,
// the std::*_distribution classes are not, so the conversions to doubles are done here.

#include <cmath>
#include <cstdint>
#include <random>

namespace lidar_sgm {
namespace synth {

/// In [0, 1).
inline double uniform01(std::mt19937& rng) { return static_cast<double>(rng()) / 4294967296.0; }

inline double uniform(std::mt19937& rng, double lo, double hi) { return lo + (hi - lo) * uniform01(rng); }

inline bool chance(std::mt19937& rng, double probability) { return uniform01(rng) < probability; }

/// Integer in [lo, hi].
inline int uniformInt(std::mt19937& rng, int lo, int hi) {
  return lo + static_cast<int>(uniform01(rng) * static_cast<double>(hi - lo + 1));
}

/// Standard normal by Box-Muller (one value per call, the partner is dropped for simplicity).
inline double gaussian(std::mt19937& rng) {
  const double u1 = (static_cast<double>(rng()) + 1.0) / 4294967297.0;  // never 0
  const double u2 = uniform01(rng);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
}

/// Integer hash of a lattice point (textures): stateless, so any pixel can be shaded alone.
inline std::uint32_t hash3(std::int64_t x, std::int64_t y, std::int64_t z, std::uint32_t seed) {
  std::uint64_t h = static_cast<std::uint64_t>(x) * 0x9E3779B97F4A7C15ull;
  h ^= static_cast<std::uint64_t>(y) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
  h ^= static_cast<std::uint64_t>(z) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
  h ^= static_cast<std::uint64_t>(seed) * 0x27D4EB2F165667C5ull;
  h ^= h >> 33;
  h *= 0xFF51AFD7ED558CCDull;
  h ^= h >> 33;
  return static_cast<std::uint32_t>(h);
}

inline double hashUnit(std::int64_t x, std::int64_t y, std::int64_t z, std::uint32_t seed) {
  return static_cast<double>(hash3(x, y, z, seed)) / 4294967296.0;
}

}  // namespace synth
}  // namespace lidar_sgm
