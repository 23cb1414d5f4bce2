// The compiled part of the Python package lidar_sgm (python/lidar_sgm/__init__.py re-exports it).
#include <pybind11/pybind11.h>

#include "bindings.hpp"
#include "errors.hpp"
#include "options.hpp"
#include "lidar_sgm/core/matcher.hpp"
#include "lidar_sgm/version.hpp"

namespace py = pybind11;

PYBIND11_MODULE(_lidar_sgm, m) {
  m.doc() = "LiDAR-SGM: dense point clouds from LiDAR and stereo, fused at the cost level of Semi-Global Matching.";
  m.attr("__version__") = lidar_sgm::versionString();
  lidar_sgm::python::registerErrors(m);
  lidar_sgm::python::bindCalibration(m);
  lidar_sgm::python::bindIo(m);
  lidar_sgm::python::bindDensifier(m);
  lidar_sgm::python::bindMatch(m);
  lidar_sgm::python::bindCloudWriter(m);
  lidar_sgm::python::bindSequence(m);
  m.def(
      "backends",
      [] {
        py::list names;
        for (lidar_sgm::Backend b : {lidar_sgm::Backend::CpuRef, lidar_sgm::Backend::Cpu, lidar_sgm::Backend::Cuda}) {
          if (lidar_sgm::isAvailable(b)) names.append(lidar_sgm::toString(b));
        }
        return names;
      },
      "backends() -> list of the backends built into this library that can run here (the `backend` parameter)");
  m.def(
      "options",
      [](bool cloud) {
        return lidar_sgm::python::parameterDefaults(cloud ? lidar_sgm::python::OptionSet::Densify
                                                          : lidar_sgm::python::OptionSet::Match);
      },
      py::arg("cloud") = true,
      "options(cloud=True) -> dict: every parameter Densifier (cloud=True) or match (cloud=False) takes, with its\n"
      "default, the same as the command-line tools' (the library's one option table)");
}
