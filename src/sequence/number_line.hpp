#pragma once
// The numbers of one line of a numeric text file (a poses file, an OXTS packet), read strictly:
// each token must be a whole, finite number.

#include <string>
#include <vector>

namespace lidar_sgm {
namespace sequence {

/// The whitespace-separated numbers of `line`. Throws std::invalid_argument "<where>: 'x' is not
/// a number" for a token that is not wholly a number (strtod alone reads "0.5m" as 0.5), and
/// "... is not a finite number" for nan, inf or an overflow.
std::vector<double> numbersOfLine(const std::string& line, const std::string& where);

}  // namespace sequence
}  // namespace lidar_sgm
