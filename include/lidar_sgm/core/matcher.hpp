#pragma once
/// @file matcher.hpp  The one entry point of the core: LiDAR-SGM on a frame, any backend.

#include <cstddef>
#include <memory>
#include <string>

#include "lidar_sgm/core/confidence.hpp"
#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/core/lidar_points.hpp"
#include "lidar_sgm/core/parameters.hpp"

namespace lidar_sgm {

enum class Backend {
  Auto,    ///< the fastest backend built into this library that can run here (cuda > cpu > cpu_ref)
  CpuRef,  ///< naive reference loops, single-threaded: the specification
  Cpu,     ///< SIMD (runtime-dispatched) + threads, bit-identical to cpu_ref
  Cuda,    ///< NVIDIA GPU (CUDA), bit-identical to cpu_ref; needs a device at run time
};

std::string toString(Backend backend);
/// "auto", "cpu_ref", "cpu", "cuda"; throws std::invalid_argument naming the accepted values.
Backend backendFromString(const std::string& name);
/// Whether this build of the library contains `backend` and it can run on this machine (cuda:
/// a CUDA device is present). Auto always is.
bool isAvailable(Backend backend);
/// "" when isAvailable(backend), else why not: "not built into this library (...)", or for cuda
/// "no CUDA device" / the driver's message.
std::string unavailableReason(Backend backend);
/// The backend Backend::Auto stands for here (never Auto): the fastest that is built and can run
/// (cuda when a device is present, else cpu, else cpu_ref); other backends map to themselves.
Backend resolve(Backend backend);
/// The instruction set the `cpu` backend dispatched to on this machine at run time ("AVX2",
/// "AVX3" (AVX-512), "SSE4", "NEON", "EMU128" ...), or "none" when the backend is not built.
std::string simdTarget();

/// Which costs a frame was matched with; decided by the inputs given to compute().
enum class MatchMode {
  StereoOnly,  ///< left + right, no LiDAR: C = C_S (alpha is not used)
  LidarOnly,   ///< LiDAR, no right image: C = C_L (alpha = 1)
  Fused,       ///< left + right + LiDAR: C = alpha*C_L + (1-alpha)*C_S (Eq. 5)
};
std::string toString(MatchMode mode);
/// toString(mode), with " (3 cameras)" appended when an up camera took part (Triple-SGM):
/// "stereo-only (3 cameras)", "fused (3 cameras)". LiDAR-only never uses cameras for costs.
std::string toString(MatchMode mode, bool upCamera);

/// Wall-clock time of each stage of the last compute() call, in milliseconds.
struct StageTimings {
  double census = 0;
  double censusCost = 0;
  double verticalCensusCost = 0;  ///< Triple-SGM only: C_V and its combination with C_S
  double lidarCost = 0;
  double fuseCosts = 0;
  double aggregatePaths = 0;
  double selectDisparity = 0;
  double leftRightCheck = 0;
  double medianFilter = 0;
  double confidence = 0;  ///< the core's part (LiDAR distance, texture, combination)
  /// cuda: copies between host and device memory (the stages above are then kernel times, from
  /// CUDA events; the stored matching cost is one kernel, timed as censusCost, lidarCost or
  /// fuseCosts by the frame's mode). 0 on the CPU backends.
  double transfers = 0;
  double total() const {
    return census + censusCost + verticalCensusCost + lidarCost + fuseCosts + aggregatePaths + selectDisparity +
           leftRightCheck + medianFilter + confidence + transfers;
  }
};

/// Triple-SGM: a third camera `baselineRatio` * b above the left one (b: the stereo baseline),
/// with the left camera's intrinsics and orientation, rectified with it vertically (same columns).
/// A point of disparity d in the left/right pair appears d * baselineRatio rows lower in `up`.
/// Default-constructed (empty `up`, ratio 0): no third camera.
struct VerticalView {
  GrayImageView up;
  double baselineRatio = 0.0;  ///< b_up / b, in (0, 4]
  bool empty() const { return up.empty(); }
};

/// Where the memory behind a view or pointer lives.
enum class MemorySpace {
  Host,    ///< ordinary host memory
  Device,  ///< memory of the current CUDA device (cudaMalloc'd, or a GPU decoder's output)
};

/// A frame that is already in GPU memory, for Matcher::computeOnDevice (the cuda backend): the
/// views and the LiDAR samples hold device pointers (row strides in elements, as on the host).
struct DeviceFrame {
  GrayImageView left;                  ///< may be empty in LiDAR-only mode (then width/height say the size)
  GrayImageView right;                 ///< empty: LiDAR-only
  const LidarSample* lidar = nullptr;  ///< `lidarCount` projected points; null: stereo-only
  std::size_t lidarCount = 0;
  int width = 0;   ///< the frame's size when `left` is empty; else ignored
  int height = 0;
  /// The cudaStream_t (as a pointer: no CUDA type in this header) on which the caller's work
  /// writes these inputs. The matcher's work on them is ordered after the work queued on it so
  /// far (an event the matcher's own stream waits for: nothing else is synchronised); nullptr is
  /// the legacy default stream, which waits for every blocking stream. computeOnDevice returns
  /// when its results are written, so work queued afterwards on any stream may read them.
  void* stream = nullptr;
};

/// Computes a dense disparity image for the left rectified camera.
///
/// @code
///   lidar_sgm::Parameters params;             // paper defaults: 128 disparities, P1 10, P2 100, alpha 0.7
///   auto matcher = lidar_sgm::Matcher::create(lidar_sgm::Backend::Auto, params);
///   lidar_sgm::Image<int16_t> disparity(width, height);
///   matcher->compute(left, right, &lidar, disparity.view());  // x16 fixed point, kInvalidDisparity
/// @endcode
///
/// A facade: the backend behind it and every buffer it keeps between frames of the same size are
/// private to the library. Not thread-safe: use one matcher per thread.
class Matcher final {
 public:
  /// Throws std::invalid_argument for invalid parameters (the message names the parameter and
  /// its allowed range) and std::runtime_error for a backend that is not built in or cannot run
  /// here (cuda without a device), saying which.
  static std::unique_ptr<Matcher> create(Backend backend, const Parameters& params = {});

  ~Matcher();
  Matcher(const Matcher&) = delete;
  Matcher& operator=(const Matcher&) = delete;

  /// The backend this matcher runs on (never Auto).
  Backend backend() const;
  const Parameters& parameters() const;
  /// Validates first; the matcher is unchanged when `params` is rejected.
  void setParameters(const Parameters& params);

  /// The mode follows from the inputs: no `lidar` (nullptr or empty) -> stereo-only; empty
  /// `right` -> LiDAR-only (then `left` may be empty too, the size comes from `lidar`); all
  /// three -> fused. `disparity` must have the frame's size; it receives x16 disparities or
  /// kInvalidDisparity. Throws std::invalid_argument naming the problem for empty or
  /// mismatched inputs.
  void compute(const GrayImageView& left, const GrayImageView& right, const LidarPoints* lidar,
               ImageView<std::int16_t> disparity);

  /// Triple-SGM: as above, plus a third camera above the left one. A non-empty `up` replaces the
  /// stereo cost C_S by C_S3 = (C_S + C_V + 1) >> 1 (C_V: census cost along the left/up columns)
  /// in stereo-only and fused mode; it needs the right image (there is no up-only mode). `up` must
  /// have the left image's size and bit depth, and baselineRatio must be finite, in (0, 4]. The
  /// left-right check still compares the left and right views only (the up view is not checked).
  /// An empty `up` (with ratio 0) is exactly the 4-argument compute().
  void compute(const GrayImageView& left, const GrayImageView& right, const VerticalView& up,
               const LidarPoints* lidar, ImageView<std::int16_t> disparity);

  /// The cuda backend: compute() on a frame already in GPU memory, the disparity written to
  /// `disparitySpace` (Device: `disparity` holds a device pointer and nothing is copied back).
  /// Results equal compute()'s on the same pixels. The LiDAR samples are read back (12 bytes a
  /// point) to be validated and bucketed as LidarPoints does; at scale 0.5 the images are read
  /// back too and the disparity is copied back, since the half-scale resampling runs on the host.
  /// Other backends throw std::runtime_error.
  void computeOnDevice(const DeviceFrame& frame, ImageView<std::int16_t> disparity,
                       MemorySpace disparitySpace = MemorySpace::Host);

  MatchMode lastMode() const;
  /// Whether the last frame was matched with the up camera too (Triple-SGM).
  bool lastUsedUpCamera() const;
  const StageTimings& lastTimings() const;
  /// 1 where a LiDAR point touched the pixel's 3x3 neighbourhood in the last frame (at the
  /// frame's full resolution, also when it was matched at scale 0.5).
  ImageView<const std::uint8_t> lidarSupport() const;
  /// Per-pixel confidence of the last frame (parameters().confidence): 0..255, close to 255 times
  /// the probability that the pixel's disparity is correct (core/confidence.hpp); 0 where the
  /// disparity is invalid. At the frame's full resolution. Empty when confidence is off.
  ImageView<const std::uint8_t> confidence() const;
  /// The inputs the confidence was computed from, at the size the frame was matched at.
  const ConfidenceInputs& confidenceInputs() const;
  /// Milliseconds spent scaling the inputs down and the disparity up in the last frame
  /// (0 at scale 1); not part of lastTimings().total().
  double lastRescaleMs() const;

 private:
  struct Impl;  // the backend, the frame's results and the core's buffers (src/core/matcher_impl.hpp)
  explicit Matcher(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace lidar_sgm
