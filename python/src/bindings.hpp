#pragma once
// One function per area adds its classes and functions to the module (module.cpp calls them).

#include <pybind11/pybind11.h>

namespace lidar_sgm {
namespace python {

void bindCalibration(pybind11::module_& module);  ///< Calibration, read_calibration
void bindIo(pybind11::module_& module);           ///< read_kitti_bin, read_cloud, read_image
void bindDensifier(pybind11::module_& module);    ///< Densifier, DensifyResult
void bindMatch(pybind11::module_& module);        ///< match
void bindCloudWriter(pybind11::module_& module);  ///< write_cloud
void bindSequence(pybind11::module_& module);     ///< Frame, frames, read_frame_calibration, sequence_poses, VoxelMap

}  // namespace python
}  // namespace lidar_sgm
