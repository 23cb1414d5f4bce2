// A user's shared library (a plugin, a Python module) that runs the core's Matcher: linking it
// is the check that a static lidar_sgm core can go into a shared object.
#include <string>

#include <lidar_sgm/core/matcher.hpp>

std::string pluginBackend() {
  return lidar_sgm::toString(lidar_sgm::Matcher::create(lidar_sgm::Backend::Auto)->backend());
}
