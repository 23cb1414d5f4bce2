// Densifier: one frame of LiDAR-SGM from numpy arrays, the same pipeline and defaults as
// lidar_sgm_densify; DensifyResult: its outputs as numpy arrays.
#include <cstring>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "densify_result.hpp"
#include "frame_images.hpp"
#include "lidar_sgm/pipeline/densifier.hpp"
#include "options.hpp"

namespace lidar_sgm {
namespace python {

namespace py = pybind11;

namespace {

/// Each point's confidence in [0, 1] (its pixel's 0..255 / 255, as the tool's `confidence` field)
/// into an (M,) array's memory: points [begin, end).
void copyPointConfidence(const Image<std::uint8_t>& confidence, const geometry::DenseCloud& cloud, float* out,
                         std::size_t begin, std::size_t end) {
  for (std::size_t i = begin; i < end; ++i) {
    const geometry::PixelIndex p = cloud.pixels[i];
    out[i] = static_cast<float>(confidence(p.x, p.y)) / 255.0f;
  }
}

/// The colors of the cloud's points (their pixels in the left image) into an (M, 3) array's memory:
/// points [begin, end).
void copyColors(const Densifier& densifier, const geometry::DenseCloud& cloud, std::uint8_t* colors,
                std::size_t begin, std::size_t end) {
  for (std::size_t i = begin; i < end; ++i) {
    const geometry::PixelIndex p = cloud.pixels[i];
    Rgb8 c;
    densifier.colorAt(p.x, p.y, c);
    colors[3 * i] = c.r;
    colors[3 * i + 1] = c.g;
    colors[3 * i + 2] = c.b;
  }
}

/// (M, cols) arrays over the cloud's own vectors, without a copy: the cloud is moved out of the
/// Densifier (each run makes a new one) into a capsule that the arrays keep alive.
template <typename T, typename Element, typename Allocator>
py::array_t<T> viewOf(std::vector<Element, Allocator>& elements, std::size_t cols, const py::capsule& owner) {
  static_assert(sizeof(Element) == 3 * sizeof(float) || sizeof(Element) == 2 * sizeof(std::int32_t),
                "a point is three packed floats, a pixel two packed ints");
  if (elements.empty()) return newArray<T>(0, cols);
  return py::array_t<T>({static_cast<py::ssize_t>(elements.size()), static_cast<py::ssize_t>(cols)},
                        {static_cast<py::ssize_t>(sizeof(Element)), static_cast<py::ssize_t>(sizeof(T))},
                        reinterpret_cast<T*>(elements.data()), owner);
}

/// The outputs of the frame `densifier` has just run. Called with the GIL held; the copies run
/// without it, on the Densifier's threads.
DensifyResult resultOf(Densifier& densifier, bool colored) {
  auto* cloud = new geometry::DenseCloud(densifier.takeCloud());
  const py::capsule owner(cloud, [](void* p) { delete static_cast<geometry::DenseCloud*>(p); });
  const auto height = static_cast<std::size_t>(densifier.disparity().height());
  const auto width = static_cast<std::size_t>(densifier.disparity().width());
  const bool haveConfidence = !densifier.confidence().empty();
  py::array_t<float> points = viewOf<float>(cloud->points, 3, owner);
  py::array_t<std::int32_t> pixels = viewOf<std::int32_t>(cloud->pixels, 2, owner);
  py::array_t<std::uint8_t> colors = newArray<std::uint8_t>(colored ? cloud->size() : 0, 3);
  py::array_t<float> disparity = newArray<float>(height, width);
  py::array_t<float> depth = newArray<float>(static_cast<std::size_t>(densifier.depth().height()),
                                             static_cast<std::size_t>(densifier.depth().width()));
  py::array_t<std::uint8_t> confidence = newArray<std::uint8_t>(haveConfidence ? height : 0, haveConfidence ? width : 0);
  py::array_t<float> pointConfidence = newArrayOfShape<float>({static_cast<py::ssize_t>(haveConfidence ? cloud->size() : 0)});
  std::uint8_t* colorsOut = colored ? colors.mutable_data() : nullptr;
  float* pointConfidenceOut = pointConfidence.mutable_data();
  float* disparityOut = disparity.mutable_data();
  float* depthOut = depth.mutable_data();
  std::uint8_t* confidenceOut = confidence.mutable_data();
  {
    py::gil_scoped_release release;
    densifier.parallelFor(cloud->size(), [&](std::size_t begin, std::size_t end) {
      if (colorsOut != nullptr) copyColors(densifier, *cloud, colorsOut, begin, end);
      if (haveConfidence) copyPointConfidence(densifier.confidence(), *cloud, pointConfidenceOut, begin, end);
    });
    densifier.parallelFor(height * width, [&](std::size_t begin, std::size_t end) {
      copyDisparity(densifier.disparity(), disparityOut, begin, end);
      if (haveConfidence) copyImage(densifier.confidence(), confidenceOut, begin, end);
    });
    const Image<float>& depthImage = densifier.depth();
    densifier.parallelFor(static_cast<std::size_t>(depthImage.width()) * static_cast<std::size_t>(depthImage.height()),
                          [&](std::size_t begin, std::size_t end) { copyImage(depthImage, depthOut, begin, end); });
  }
  DensifyResult r;
  r.points = std::move(points);
  r.colors = colored ? py::object(std::move(colors)) : py::object(py::none());
  r.pixels = std::move(pixels);
  r.disparity = std::move(disparity);
  r.depth = std::move(depth);
  r.confidence = haveConfidence ? py::object(std::move(confidence)) : py::object(py::none());
  r.pointConfidence = haveConfidence ? py::object(std::move(pointConfidence)) : py::object(py::none());
  const DensificationTimings& t = densifier.timings();
  r.timings["project"] = t.project;
  r.timings["match"] = t.match;
  r.timings["filters"] = t.filters;  // part of match
  r.timings["reproject"] = t.reproject;
  r.timings["total"] = t.total();
  const geometry::ProjectionStats& s = densifier.projected().stats;
  r.projection["input"] = s.input;
  r.projection["non_finite"] = s.nonFinite;
  r.projection["behind_camera"] = s.behindCamera;
  r.projection["out_of_range"] = s.outOfRange;
  r.projection["outside_image"] = s.outsideImage;
  r.projection["occluded"] = s.occluded;
  r.projection["kept"] = s.kept;
  r.mode = toString(densifier.lastMode());
  r.backend = toString(densifier.usedBackend());
  r.frame = densifier.reprojectionOptions().frame == geometry::OutputFrame::Camera ? "camera" : "lidar";
  r.disparityRange = py::make_tuple(densifier.usedParameters().minDisparity, densifier.usedParameters().numDisparities);
  r.width = cloud->width;
  r.height = cloud->height;
  r.isDense = cloud->isDense;
  return r;
}

/// The calibration argument as a Calibration; TypeError otherwise, saying how to get one (a path
/// is the likely mistake: the tools take one, as -calib).
const geometry::StereoCalibration& calibrationArgument(const py::object& calibration) {
  if (py::isinstance<geometry::StereoCalibration>(calibration)) return calibration.cast<const geometry::StereoCalibration&>();
  const std::string type = py::str(py::type::handle_of(calibration).attr("__name__"));
  const bool path = py::isinstance<py::str>(calibration) || py::hasattr(calibration, "__fspath__");
  throw py::type_error("Densifier(calibration): expected a lidar_sgm.Calibration, got " + type +
                       (path ? " " + std::string(py::repr(calibration)) + "; read the file with lidar_sgm.read_calibration(path)"
                             : "; read one from a file with lidar_sgm.read_calibration(path), or build one with "
                               "lidar_sgm.Calibration(K, baseline, T_cam_lidar)"));
}

class PyDensifier {
 public:
  PyDensifier(const py::object& calibration, const py::kwargs& parameters) : parameters_(parameters) {
    const geometry::StereoCalibration& checked = calibrationArgument(calibration);
    configure(densifier_, parameters_, OptionSet::Densify);
    densifier_.setCalibration(checked);
  }

  DensifyResult densify(const py::object& points, const py::object& left, const py::object& right) {
    std::vector<Eigen::Vector3f> lidar;
    pointsFromArray(points, lidar);
    const FrameImages images = frameImages(left, right);
    // One frame at a time per Densifier (it holds the frame's buffers), until its outputs are
    // copied out. The lock is only ever taken without the GIL, so holding it while the GIL is
    // taken back cannot deadlock.
    std::unique_lock<std::mutex> lock(mutex_, std::defer_lock);
    {
      // Matching takes ~100 ms: other Python threads run meanwhile.
      py::gil_scoped_release release;
      lock.lock();
      setImages(densifier_, images, true);
      densifier_.run(lidar);
    }
    return resultOf(densifier_, !images.left.mat.empty());
  }

  geometry::StereoCalibration calibration() const { return densifier_.calibration(); }
  py::dict parameters() const { return py::dict(parameters_); }

 private:
  Densifier densifier_;
  std::mutex mutex_;
  py::dict parameters_;
};

}  // namespace

void bindDensifier(py::module_& m) {
  py::class_<DensifyResult>(m, "DensifyResult", "The outputs of one Densifier.densify call (they own their memory: they stay valid).")
      .def_readonly("points", &DensifyResult::points,
                    "(M, 3) float32 points [m], in the output frame (`frame`: LiDAR by default); NaN rows for\n"
                    "pixels without a point when keep_organized")
      .def_readonly("colors", &DensifyResult::colors, "(M, 3) uint8 RGB from the left image; None without one")
      .def_readonly("pixels", &DensifyResult::pixels, "(M, 2) int32: the (x, y) pixel of each point")
      .def_readonly("point_confidence", &DensifyResult::pointConfidence,
                    "(M,) float32 in [0, 1], aligned with points: each point's confidence (its pixel's\n"
                    "confidence / 255), the `confidence` field of lidar_sgm_densify's cloud; None with no_confidence")
      .def_readonly("disparity", &DensifyResult::disparity, "(H, W) float32 disparity [px], NaN where there is none")
      .def_readonly("depth", &DensifyResult::depth,
                    "(H, W) float32 depth z [m] in the left camera (Eq. 3), 0 where none or beyond max_depth")
      .def_readonly("confidence", &DensifyResult::confidence,
                    "(H, W) uint8: 255 x the probability that the disparity is right, 0 where none;\n"
                    "None with no_confidence")
      .def_readonly("timings", &DensifyResult::timings, "milliseconds: project, match (filters: its part after the matcher), reproject, total")
      .def_readonly("projection", &DensifyResult::projection,
                    "what happened to the input points: input, non_finite, behind_camera, out_of_range,\n"
                    "outside_image, occluded, kept")
      .def_readonly("mode", &DensifyResult::mode, "'fused', 'lidar-only' or 'stereo-only'")
      .def_readonly("backend", &DensifyResult::backend, "the backend that matched ('cpu', 'cpu_ref', 'cuda')")
      .def_readonly("frame", &DensifyResult::frame, "the points' frame: 'lidar' or 'camera'")
      .def_readonly("disparity_range", &DensifyResult::disparityRange, "(min_disparity, num_disparities) matched")
      .def_readonly("width", &DensifyResult::width, "keep_organized: sampled columns; else the number of points")
      .def_readonly("height", &DensifyResult::height, "keep_organized: sampled rows; else 1")
      .def("__repr__", [](const DensifyResult& r) {
        return "<lidar_sgm.DensifyResult " + r.mode + ", " + std::to_string(py::len(r.points)) + " points>";
      });

  static const std::string doc =
      "Densifier(calibration, **parameters)\n\n"
      "One frame of LiDAR-SGM, end to end (project the scan, match, filter, reproject): the pipeline and\n"
      "the defaults of lidar_sgm_densify. Keeps its buffers between frames; one frame at a time (calls\n"
      "from several threads wait for each other). calibration: a Calibration (lidar_sgm.read_calibration(path)\n"
      "reads the tools' -calib files; TypeError for anything else). ValueError for an unknown or invalid\n"
      "parameter.\n\n" +
      parametersHelp(OptionSet::Densify);
  py::class_<PyDensifier>(m, "Densifier", doc.c_str())
      .def(py::init<const py::object&, const py::kwargs&>(), py::arg("calibration"))
      .def("densify", &PyDensifier::densify, py::arg("points"), py::arg("left") = py::none(),
           py::arg("right") = py::none(),
           "densify(points, left=None, right=None) -> DensifyResult\n\n"
           "points: (N, 3) or (N, 4) float32/float64, LiDAR frame [m] (a 4th column, intensity, is ignored).\n"
           "left, right: rectified (H, W) gray or (H, W, 3) RGB images, uint8 or uint16 (read without a copy\n"
           "where each row's pixels are contiguous). Both -> fused LiDAR-SGM (Eq. 5); left alone -> LiDAR-only,\n"
           "colored from left; neither -> LiDAR-only, no colors. The GIL is released while densifying.\n"
           "ValueError for bad arrays, sizes or a frame that cannot be matched (the C++ message).")
      .def_property_readonly("calibration", &PyDensifier::calibration, "the Calibration given")
      .def_property_readonly("parameters", &PyDensifier::parameters, "the keyword parameters given (a copy)");
}

}  // namespace python
}  // namespace lidar_sgm
