#pragma once
// numpy arrays in and out: LiDAR points, images (as views where the layout allows), and the
// Densifier's outputs as new arrays (the Densifier reuses its buffers on the next frame).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "lidar_sgm/core/huge_page_allocator.hpp"
#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/geometry/reprojection.hpp"

namespace lidar_sgm {
namespace python {

namespace py = pybind11;

/// An (N, 3) or (N, 4) float32 / float64 array (x, y, z [, intensity], any strides) into
/// `points` (x, y, z as float, as PCL and the .bin files hold them). ValueError otherwise.
void pointsFromArray(const py::handle& array, std::vector<Eigen::Vector3f>& points);

/// A camera image: (H, W) gray or (H, W, 3) RGB, uint8 or uint16, wrapped without a copy when
/// its rows are contiguous pixels (any row stride); otherwise copied once into a C-contiguous
/// array, which `owner` keeps alive.
struct ImageArray {
  cv::Mat mat;      ///< RGB order for 3 channels; points into the array's memory
  py::object owner; ///< the array `mat` points into
};
/// ValueError naming `name`, the expected layouts and what was given.
ImageArray imageFromArray(const py::handle& array, const char* name);

/// What the tool matches: the gray levels at full depth (cv::cvtColor's BT.601 weights, as
/// lidar_sgm::io::toGray; gray images are returned as they are, not copied).
cv::Mat grayOf(const cv::Mat& image);
/// What the tool colors the output with (lidar_sgm::io::toColor, in RGB order): 16 bit scaled
/// by 1/257, gray expanded. An 8-bit RGB image is returned as it is, not copied.
cv::Mat colorOf(const cv::Mat& image);
/// A view of an 8-bit, 3-channel cv::Mat as Rgb8 pixels (no copy).
ImageView<const Rgb8> rgbView(const cv::Mat& rgb);

// Outputs: arrays are made with the GIL held (newArray), then filled without it (copy*), so that
// other Python threads run while a frame's ~12 MB of outputs are copied.

/// A new, uninitialised array of `shape` (1 or 2 dimensions). One of kHugePageThreshold bytes or
/// more lies on transparent huge pages (allocateHugePages), which the array owns: every call's
/// outputs are new memory, and on 4 KiB pages its first write costs a page fault per 4 KiB (on
/// the project's VM ~14 us each: ~8 ms of a KITTI frame's ~7 MB of outputs; BENCHMARK.md, "The
/// Python module's overhead").
template <typename T>
py::array_t<T> newArrayOfShape(const std::vector<py::ssize_t>& shape) {
  std::size_t count = 1;
  for (const py::ssize_t n : shape) count *= static_cast<std::size_t>(n);
  if (count * sizeof(T) < kHugePageThreshold) return py::array_t<T>(shape);
  // The block of a HugePageAllocator, freed by it when the capsule (the array's base) goes.
  struct Block {
    T* data;
    std::size_t count;
    Block(const Block&) = delete;
    Block& operator=(const Block&) = delete;
    ~Block() { HugePageAllocator<T>().deallocate(data, count); }
  };
  // Allocated in place (a new-expression allocates before it evaluates its initializer, and frees
  // again if the pages cannot be had).
  std::unique_ptr<Block> block(new Block{HugePageAllocator<T>().allocate(count), count});
  T* data = block->data;
  py::capsule owner(block.get(), [](void* p) { delete static_cast<Block*>(p); });
  block.release();  // the capsule owns it now
  return py::array_t<T>(shape, data, owner);
}
/// A new, uninitialised rows x cols array (newArrayOfShape).
template <typename T>
py::array_t<T> newArray(std::size_t rows, std::size_t cols) {
  return newArrayOfShape<T>({static_cast<py::ssize_t>(rows), static_cast<py::ssize_t>(cols)});
}
/// x16 disparities (kInvalidDisparity) -> float [px], NaN where there is none, into `out`
/// (width x height, row-major); pixels [begin, end) of the row-major order only, where given.
void copyDisparity(const Image<std::int16_t>& disparity16, float* out);
void copyDisparity(const Image<std::int16_t>& disparity16, float* out, std::size_t begin, std::size_t end);
/// The pixels of `image` into `out` (width x height, row-major); [begin, end) only, where given.
template <typename T>
void copyImage(const Image<T>& image, T* out, std::size_t begin, std::size_t end) {
  std::copy(image.data() + begin, image.data() + end, out + begin);
}
template <typename T>
void copyImage(const Image<T>& image, T* out) {
  copyImage(image, out, 0, static_cast<std::size_t>(image.width()) * image.height());
}
/// x16 disparities -> a new (H, W) float32 array, NaN where there is none (with the GIL).
py::array_t<float> disparityArray(const Image<std::int16_t>& disparity16);

/// "shape (2, 3) float64": what was given, for messages.
std::string describeArray(const py::handle& array);

}  // namespace python
}  // namespace lidar_sgm
