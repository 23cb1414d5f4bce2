// libsgm_bench: libSGM (github.com/fixstars/libSGM, Apache-2.0, not part of this repository) on
// the frame the lidar_sgm bench times on the GPU, with settings as close to ours as libSGM
// takes, so that scripts/gpu_check.sh can print our time beside it.
//
//   libsgm_bench FRAME_DIR [-paths 4|8] [-runs N] [-warmups N]
//
// FRAME_DIR holds left.pgm and right.pgm (8-bit P5, as lidar_sgm_bench -export_frame writes
// them). Prints a settings block and one line for scripts:
//   libsgm paths=4 disparities=128 runs=100 median_ms=... with_transfers_ms=... valid_pct=...
// median_ms: CUDA events around StereoSGM::execute with the images already on the device.
// with_transfers_ms: the same around the upload of both images, execute and the download of
// the disparity (pageable host memory, as a caller's images are).
// Built by scripts/gpu_check.sh with nvcc, together with libSGM's sources.
#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include <cuda_runtime.h>

#include "libsgm.h"

namespace {

void check(cudaError_t status, const char* what) {
  if (status != cudaSuccess) throw std::runtime_error(std::string(what) + ": " + cudaGetErrorString(status));
}

struct Gray8 {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;
};

/// An 8-bit binary PGM (P5, maxval < 256; '#' comments in the header allowed).
Gray8 readPgm8(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot be opened");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.size() < 2 || bytes.compare(0, 2, "P5") != 0) throw std::runtime_error(path + ": not a binary PGM (P5)");
  std::size_t pos = 2;
  int fields[3] = {0, 0, 0};
  for (int& field : fields) {
    while (pos < bytes.size() && (std::isspace(static_cast<unsigned char>(bytes[pos])) || bytes[pos] == '#')) {
      if (bytes[pos] == '#') {
        while (pos < bytes.size() && bytes[pos] != '\n') ++pos;
      } else {
        ++pos;
      }
    }
    const std::size_t start = pos;
    while (pos < bytes.size() && std::isdigit(static_cast<unsigned char>(bytes[pos])) && field <= 65535) {
      field = field * 10 + (bytes[pos++] - '0');
    }
    if (pos == start || field < 1 || field > 65535) throw std::runtime_error(path + ": malformed PGM header");
  }
  if (fields[2] > 255) throw std::runtime_error(path + ": not an 8-bit PGM (maxval " + std::to_string(fields[2]) + ")");
  ++pos;  // the one whitespace after maxval
  Gray8 image;
  image.width = fields[0];
  image.height = fields[1];
  const std::size_t size = static_cast<std::size_t>(image.width) * image.height;
  if (pos > bytes.size() || bytes.size() - pos < size) throw std::runtime_error(path + ": PGM raster is truncated");
  image.pixels.assign(bytes.begin() + static_cast<std::ptrdiff_t>(pos),
                      bytes.begin() + static_cast<std::ptrdiff_t>(pos + size));
  return image;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t mid = values.size() / 2;
  return values.size() % 2 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
}

/// Milliseconds between two events around `fn` on the default stream (libSGM's).
template <typename Fn>
double eventMs(cudaEvent_t start, cudaEvent_t stop, Fn&& fn) {
  check(cudaEventRecord(start), "cudaEventRecord");
  fn();
  check(cudaEventRecord(stop), "cudaEventRecord");
  check(cudaEventSynchronize(stop), "cudaEventSynchronize");
  float ms = 0;
  check(cudaEventElapsedTime(&ms, start, stop), "cudaEventElapsedTime");
  return ms;
}

int integerOption(int argc, char** argv, const std::string& name, int fallback) {
  for (int i = 2; i + 1 < argc; ++i) {
    if (argv[i] == name) return std::stoi(argv[i + 1]);
  }
  return fallback;
}

int run(int argc, char** argv) {
  if (argc < 2 || argc % 2 != 0) {
    throw std::invalid_argument("usage: libsgm_bench FRAME_DIR [-paths 4|8] [-runs N] [-warmups N]");
  }
  for (int i = 2; i < argc; i += 2) {
    const std::string option = argv[i];
    if (option != "-paths" && option != "-runs" && option != "-warmups") {
      throw std::invalid_argument("unknown option " + option + " (-paths, -runs, -warmups)");
    }
  }
  const std::string folder = argv[1];
  const int paths = integerOption(argc, argv, "-paths", 4);
  const int runs = integerOption(argc, argv, "-runs", 100);
  const int warmups = integerOption(argc, argv, "-warmups", 10);
  if (paths != 4 && paths != 8) throw std::invalid_argument("-paths must be 4 or 8");
  if (runs < 1 || warmups < 0) throw std::invalid_argument("-runs must be >= 1 and -warmups >= 0");
  const int disparities = 128;

  const Gray8 left = readPgm8(folder + "/left.pgm");
  const Gray8 right = readPgm8(folder + "/right.pgm");
  if (left.width != right.width || left.height != right.height) {
    throw std::runtime_error("left.pgm and right.pgm differ in size");
  }
  const int width = left.width;
  const int height = left.height;

  // Our defaults where libSGM has the same setting: P1 10, P2 100 (libSGM's default P2 is 120),
  // no uniqueness test (1.0; ours: uniquenessRatio 0), left-right check with 2 px (ours:
  // disp12MaxDiff 2; libSGM's default is 1), subpixel, the plain 9x7 census (libSGM's default is
  // the symmetric one).
  // libSGM's median filter is 3x3 and always on (ours: 5x5).
  sgm::StereoSGM::Parameters params(10, 100, 1.0f, true,
                                    paths == 8 ? sgm::PathType::SCAN_8PATH : sgm::PathType::SCAN_4PATH, 0, 2,
                                    sgm::CensusType::CENSUS_9x7);

  int device = 0;
  cudaDeviceProp properties{};
  check(cudaGetDevice(&device), "cudaGetDevice");
  check(cudaGetDeviceProperties(&properties, device), "cudaGetDeviceProperties");
  std::printf("libsgm_bench (libSGM %d.%d.%d)\n", LIBSGM_VERSION_MAJOR, LIBSGM_VERSION_MINOR, LIBSGM_VERSION_PATCH);
  std::printf("  device:       %s (sm_%d%d)\n", properties.name, properties.major, properties.minor);
  std::printf("  input:        %s/{left,right}.pgm, %dx%d, 8-bit\n", folder.c_str(), width, height);
  std::printf("  settings:     %d disparities, %d paths, census 9x7, P1 %d, P2 %d, uniqueness %.2f (off), "
              "LR max diff %d, subpixel, 3x3 median\n",
              disparities, paths, params.P1, params.P2, static_cast<double>(params.uniqueness), params.LR_max_diff);
  std::printf("  timing:       median of %d runs after %d warm-up runs, CUDA events\n", runs, warmups);

  const std::size_t imageBytes = static_cast<std::size_t>(width) * height;
  std::uint8_t* dLeft = nullptr;
  std::uint8_t* dRight = nullptr;
  std::uint16_t* dDisparity = nullptr;
  check(cudaMalloc(&dLeft, imageBytes), "cudaMalloc");
  check(cudaMalloc(&dRight, imageBytes), "cudaMalloc");
  check(cudaMalloc(&dDisparity, imageBytes * sizeof(std::uint16_t)), "cudaMalloc");
  std::vector<std::uint16_t> disparity(imageBytes);

  sgm::StereoSGM sgm(width, height, disparities, 8, 16, sgm::EXECUTE_INOUT_CUDA2CUDA, params);
  cudaEvent_t start = nullptr;
  cudaEvent_t stop = nullptr;
  check(cudaEventCreate(&start), "cudaEventCreate");
  check(cudaEventCreate(&stop), "cudaEventCreate");

  const auto upload = [&] {
    check(cudaMemcpy(dLeft, left.pixels.data(), imageBytes, cudaMemcpyHostToDevice), "cudaMemcpy left");
    check(cudaMemcpy(dRight, right.pixels.data(), imageBytes, cudaMemcpyHostToDevice), "cudaMemcpy right");
  };
  const auto execute = [&] { sgm.execute(dLeft, dRight, dDisparity); };
  const auto download = [&] {
    check(cudaMemcpy(disparity.data(), dDisparity, imageBytes * sizeof(std::uint16_t), cudaMemcpyDeviceToHost),
          "cudaMemcpy disparity");
  };

  upload();
  for (int i = 0; i < warmups; ++i) execute();
  check(cudaDeviceSynchronize(), "warm-up");
  std::vector<double> kernelMs, withTransfersMs;
  for (int i = 0; i < runs; ++i) kernelMs.push_back(eventMs(start, stop, execute));
  for (int i = 0; i < runs; ++i) {
    withTransfersMs.push_back(eventMs(start, stop, [&] {
      upload();
      execute();
      download();
    }));
  }
  check(cudaGetLastError(), "libSGM kernels");

  // A run that produced nothing must not pass for a fast one.
  const int invalid = sgm.get_invalid_disparity();
  std::size_t valid = 0;
  for (const std::uint16_t d : disparity) valid += static_cast<std::int16_t>(d) != invalid;
  const double validPct = 100.0 * static_cast<double>(valid) / static_cast<double>(imageBytes);
  std::printf("  valid:        %.1f %% of the pixels have a disparity\n", validPct);
  std::printf("libsgm paths=%d disparities=%d runs=%d median_ms=%.3f with_transfers_ms=%.3f valid_pct=%.1f\n", paths,
              disparities, runs, median(kernelMs), median(withTransfersMs), validPct);

  cudaEventDestroy(start);
  cudaEventDestroy(stop);
  cudaFree(dLeft);
  cudaFree(dRight);
  cudaFree(dDisparity);
  return valid > 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "libsgm_bench: %s\n", e.what());
    return 1;
  }
}
