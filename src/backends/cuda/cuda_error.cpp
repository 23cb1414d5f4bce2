#include "backends/cuda/cuda_error.hpp"

#include <stdexcept>
#include <string>

namespace lidar_sgm {
namespace cuda {

void throwCudaError(cudaError_t error, const char* call, const char* file, int line) {
  // Clear a non-sticky error so the next call on this thread does not report it again.
  (void)cudaGetLastError();
  throw std::runtime_error(std::string("CUDA error in ") + call + " (" + file + ":" + std::to_string(line) +
                           "): " + cudaGetErrorName(error) + ": " + cudaGetErrorString(error));
}

}  // namespace cuda
}  // namespace lidar_sgm
