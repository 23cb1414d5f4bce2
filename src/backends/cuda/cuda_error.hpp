#pragma once
/// @file cuda_error.hpp  CUDA runtime errors as exceptions: a failed call throws
/// std::runtime_error naming the call, the file/line and CUDA's message. (libSGM's CUDA_CHECK
/// prints and carries on; a densification that silently used garbage is worse than none.)

#include <cuda_runtime_api.h>

namespace lidar_sgm {
namespace cuda {

/// Throws std::runtime_error("CUDA error in <call> (<file>:<line>): <name>: <message>").
[[noreturn]] void throwCudaError(cudaError_t error, const char* call, const char* file, int line);

inline void checkCuda(cudaError_t error, const char* call, const char* file, int line) {
  if (error != cudaSuccess) throwCudaError(error, call, file, line);
}

}  // namespace cuda
}  // namespace lidar_sgm

/// Wraps a CUDA runtime call: LIDAR_SGM_CUDA_CHECK(cudaMalloc(&p, n));
#define LIDAR_SGM_CUDA_CHECK(call) ::lidar_sgm::cuda::checkCuda((call), #call, __FILE__, __LINE__)
/// After a kernel launch: the launch's own error (bad configuration, no device code for this GPU).
#define LIDAR_SGM_CUDA_CHECK_LAUNCH(kernelName) \
  ::lidar_sgm::cuda::checkCuda(cudaGetLastError(), "launch of " kernelName, __FILE__, __LINE__)
