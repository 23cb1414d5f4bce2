#pragma once
// Output files shared by the tools: never overwrite an input, right extension (written whole or
// not at all by io::AtomicFile).

#include <string>
#include <vector>

namespace lidar_sgm {
namespace apps {

/// Whether two paths name the same file (existing or not).
bool samePath(const std::string& a, const std::string& b);

/// Throws std::invalid_argument when `path`'s extension (lower case, with the dot) is not one
/// of `extensions`, or when `path` is one of `inputs` ("refusing to overwrite an input").
void requireOutput(const std::string& path, const std::vector<std::string>& extensions,
                   const std::vector<std::string>& inputs);

/// Lower-case extension with the dot ("" when there is none).
std::string lowerExtension(const std::string& path);


}  // namespace apps
}  // namespace lidar_sgm
