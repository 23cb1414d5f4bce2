#pragma once
/// @file option_text.hpp  An option's value read from text, with the message every front end
/// gives for a bad one (the tools' command lines, Python's keywords, the option table).

#include <string>

namespace lidar_sgm {

/// `text` as a whole number within +-1e9; std::invalid_argument "option -name: 'text' is not an
/// integer" otherwise.
int parseOptionInteger(const std::string& name, const std::string& text);

/// `text` as a finite number; std::invalid_argument "option -name: 'text' is not a finite
/// number" otherwise.
double parseOptionNumber(const std::string& name, const std::string& text);

}  // namespace lidar_sgm
