#pragma once
// Wall-clock milliseconds for the tools' "[done, N ms : ...]" lines.

#include <chrono>

namespace lidar_sgm {
namespace apps {

class Timer {
 public:
  double elapsedMs() const {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace apps
}  // namespace lidar_sgm
