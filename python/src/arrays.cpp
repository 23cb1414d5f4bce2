#include "arrays.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

namespace lidar_sgm {
namespace python {

std::string describeArray(const py::handle& array) {
  if (!py::isinstance<py::array>(array)) return std::string("a ") + py::str(array.get_type().attr("__name__")).cast<std::string>();
  const py::array a = py::reinterpret_borrow<py::array>(array);
  std::string shape = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) shape += (i ? ", " : "") + std::to_string(a.shape(i));
  if (a.ndim() == 1) shape += ",";
  return "shape " + shape + ") " + py::str(a.dtype()).cast<std::string>();
}

namespace {

template <typename T>
void copyPoints(const py::array& array, std::vector<Eigen::Vector3f>& points) {
  // unchecked<T, 2> reads through the strides: a column slice or a transposed array needs no copy.
  const auto a = array.unchecked<T, 2>();
  points.resize(static_cast<std::size_t>(a.shape(0)));
  for (py::ssize_t i = 0; i < a.shape(0); ++i) {
    points[static_cast<std::size_t>(i)] =
        Eigen::Vector3f(static_cast<float>(a(i, 0)), static_cast<float>(a(i, 1)), static_cast<float>(a(i, 2)));
  }
}

bool isUint8(const py::handle& a) { return py::isinstance<py::array_t<std::uint8_t>>(a); }
bool isUint16(const py::handle& a) { return py::isinstance<py::array_t<std::uint16_t>>(a); }

/// Whether cv::Mat can wrap the array as it is: pixels (and channels) packed in each row, rows
/// a non-negative multiple of the element size apart.
bool wrappable(const py::array& a) {
  const py::ssize_t item = a.itemsize();
  const py::ssize_t channels = a.ndim() == 3 ? a.shape(2) : 1;
  if (a.ndim() == 3 && a.strides(2) != item) return false;
  if (a.strides(1) != item * channels) return false;
  return a.strides(0) >= a.shape(1) * item * channels && a.strides(0) % item == 0;
}

}  // namespace

void pointsFromArray(const py::handle& array, std::vector<Eigen::Vector3f>& points) {
  const bool f32 = py::isinstance<py::array_t<float>>(array);
  const bool f64 = py::isinstance<py::array_t<double>>(array);
  const py::array a = (f32 || f64) ? py::reinterpret_borrow<py::array>(array) : py::array();
  if (!(f32 || f64) || a.ndim() != 2 || (a.shape(1) != 3 && a.shape(1) != 4)) {
    throw std::invalid_argument("points: expected an (N, 3) or (N, 4) array of float32 or float64 (x, y, z [, "
                                "intensity], LiDAR frame, metres), got " + describeArray(array));
  }
  if (f32) {
    copyPoints<float>(a, points);
  } else {
    copyPoints<double>(a, points);
  }
}

ImageArray imageFromArray(const py::handle& array, const char* name) {
  const bool u8 = isUint8(array);
  const bool u16 = isUint16(array);
  py::array a = (u8 || u16) ? py::reinterpret_borrow<py::array>(array) : py::array();
  const bool shapeOk = (u8 || u16) && (a.ndim() == 2 || (a.ndim() == 3 && a.shape(2) == 3)) && a.shape(0) > 0 &&
                       a.shape(1) > 0;
  if (!shapeOk) {
    throw std::invalid_argument(std::string(name) + ": expected an (H, W) gray or (H, W, 3) RGB array of uint8 or "
                                "uint16, got " + describeArray(array));
  }
  if (!wrappable(a)) a = py::array::ensure(a, py::array::c_style);  // e.g. every other column
  const int channels = a.ndim() == 3 ? 3 : 1;
  const int type = CV_MAKETYPE(u8 ? CV_8U : CV_16U, channels);
  ImageArray out;
  // cv::Mat never writes here: the images are inputs only.
  out.mat = cv::Mat(static_cast<int>(a.shape(0)), static_cast<int>(a.shape(1)), type, const_cast<void*>(a.data()),
                    static_cast<std::size_t>(a.strides(0)));
  out.owner = a;
  return out;
}

cv::Mat grayOf(const cv::Mat& image) {
  if (image.channels() == 1) return image;
  cv::Mat gray;
  // RGB2GRAY on RGB is BGR2GRAY on the same pixels stored BGR (the tool's), value for value.
  cv::cvtColor(image, gray, cv::COLOR_RGB2GRAY);
  return gray;
}

cv::Mat colorOf(const cv::Mat& image) {
  cv::Mat color = image;
  if (color.depth() == CV_16U) color.convertTo(color, CV_8U, 1.0 / 257.0);
  if (color.channels() == 1) cv::cvtColor(color, color, cv::COLOR_GRAY2RGB);
  return color;
}

ImageView<const Rgb8> rgbView(const cv::Mat& rgb) {
  static_assert(sizeof(Rgb8) == 3, "Rgb8 must be three packed bytes to view RGB rows");
  if (rgb.type() != CV_8UC3 || rgb.step % 3 != 0) throw std::logic_error("rgbView: not packed 8-bit RGB rows");
  return ImageView<const Rgb8>(reinterpret_cast<const Rgb8*>(rgb.data), rgb.cols, rgb.rows,
                               static_cast<std::ptrdiff_t>(rgb.step / 3));
}

void copyDisparity(const Image<std::int16_t>& disparity16, float* out) {
  copyDisparity(disparity16, out, 0,
                static_cast<std::size_t>(disparity16.width()) * static_cast<std::size_t>(disparity16.height()));
}

void copyDisparity(const Image<std::int16_t>& disparity16, float* out, std::size_t begin, std::size_t end) {
  const std::int16_t* d = disparity16.data();
  for (std::size_t i = begin; i < end; ++i) {
    out[i] = d[i] == kInvalidDisparity ? std::numeric_limits<float>::quiet_NaN()
                                       : static_cast<float>(d[i]) / static_cast<float>(kDisparityScale);
  }
}

py::array_t<float> disparityArray(const Image<std::int16_t>& disparity16) {
  py::array_t<float> out = newArray<float>(static_cast<std::size_t>(disparity16.height()),
                                           static_cast<std::size_t>(disparity16.width()));
  copyDisparity(disparity16, out.mutable_data());
  return out;
}

}  // namespace python
}  // namespace lidar_sgm
