#pragma once
/// @file host_device.hpp  Marks the small integer helpers that every backend shares (stages.hpp)
/// as callable from CUDA kernels too, so that the GPU runs the very same arithmetic as cpu_ref.

#ifdef __CUDACC__
#define LIDAR_SGM_HOST_DEVICE __host__ __device__
#else
#define LIDAR_SGM_HOST_DEVICE
#endif
