#pragma once
// How the reports write numbers into Markdown cells: fixed decimals, shares in percent.

#include <cstdio>
#include <string>

namespace lidar_sgm {
namespace eval {

/// `value` with `decimals` decimals ("%.*f").
inline std::string fixed(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.*f", decimals, value);
  return text;
}

/// A share in [0, 1] as percent with `decimals` decimals.
inline std::string percent(double share, int decimals = 2) { return fixed(100.0 * share, decimals); }

}  // namespace eval
}  // namespace lidar_sgm
