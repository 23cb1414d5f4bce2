#pragma once
// A frame's camera images into the Densifier, as lidar_sgm_densify sets its decoded files
// (apps::setImages): a pair -> matched on its gray levels at full depth; left -> the colors.

#include "arrays.hpp"
#include "lidar_sgm/pipeline/densifier.hpp"

namespace lidar_sgm {
namespace python {

/// The images of one call, checked and wrapped (with the GIL held).
struct FrameImages {
  ImageArray left;   ///< empty mat: none
  ImageArray right;  ///< empty mat: none
};
/// ValueError for a right image without a left one, or a bad array.
FrameImages frameImages(const pybind11::object& left, const pybind11::object& right);

/// Sets (or clears) the stereo pair and, with `color`, the color image from `images`. Touches no
/// Python object: call it with the GIL released.
void setImages(Densifier& densifier, const FrameImages& images, bool color);

}  // namespace python
}  // namespace lidar_sgm
