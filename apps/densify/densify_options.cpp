#include "densify/densify_options.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <stdexcept>

namespace lidar_sgm {
namespace apps {

OutputOptions outputOptionsFrom(const Arguments& args) {
  OutputOptions o;
  try {
    o.format = io::cloudFormatFromString(args.text("format", "binary"));
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("option -format: ") + e.what());
  }
  o.voxel = args.number("voxel", o.voxel);
  if (!(o.voxel >= 0.0) || !std::isfinite(o.voxel)) {
    throw std::invalid_argument("option -voxel: must be a finite edge >= 0 [m] (0 = no down-sampling)");
  }
  if (o.voxel > 0.0 && args.has("keep_organized")) {
    throw std::invalid_argument("option -voxel: a down-sampled cloud has no pixel grid; drop -keep_organized");
  }
  return o;
}

void parseImageSize(const std::string& text, int& width, int& height, const char* option) {
  const std::size_t x = text.find('x');
  try {
    std::size_t used = 0;
    if (x == std::string::npos) throw std::invalid_argument("no x");
    width = std::stoi(text.substr(0, x), &used);
    if (used != x) throw std::invalid_argument("trailing");
    height = std::stoi(text.substr(x + 1), &used);
    if (used != text.size() - x - 1) throw std::invalid_argument("trailing");
  } catch (const std::exception&) {
    throw std::invalid_argument(std::string("option -") + option + ": '" + text +
                                "' is not WIDTHxHEIGHT (e.g. 1242x375)");
  }
  if (width <= 0 || height <= 0) {
    throw std::invalid_argument(std::string("option -") + option + ": '" + text + "' must be positive");
  }
  // The images' limit (io::kMaxImageSide): a larger size would only fail later, allocating.
  if (width > io::kMaxImageSide || height > io::kMaxImageSide) {
    throw std::invalid_argument(std::string("option -") + option + ": '" + text + "' is larger than the limit of " +
                                std::to_string(io::kMaxImageSide) + "x" + std::to_string(io::kMaxImageSide) +
                                " pixels");
  }
}

void requireOrganizedImage(const std::string& path, const cv::Mat& image) {
  if (image.cols < 2 || image.rows < 2) {
    throw std::invalid_argument("the image '" + path + "' is " + std::to_string(image.cols) + "x" +
                                std::to_string(image.rows) +
                                ": an image needs at least 2x2 pixels (it becomes an organized point cloud)");
  }
}

std::set<std::string> densifyValueOptions() {
  return joined(configValueOptions(OptionScope::Cloud), {"image_size", "format", "voxel", "max_points"});
}

std::set<std::string> densifyFlagOptions() { return configFlagOptions(OptionScope::Cloud); }

std::string outputOptionsHelp() {
  return "  -format binary|compressed|ascii\n"
         "                           OUTPUT's encoding: binary (PCD DATA binary, PLY binary_little_endian; the\n"
         "                           fastest), compressed (PCD binary_compressed: PCL's LZF, 10-20x slower and\n"
         "                           only ~3 % smaller for a dense cloud; not for PLY) or ascii (text, ~60x\n"
         "                           slower) (default: binary)\n" +
         optionsHelp(OptionGroup::Output, OptionScope::Cloud) +
         "  -voxel V                 down-sample to one point per V-metre voxel (pcl::VoxelGrid: the centroid,\n"
         "                           color and confidence averaged; unorganized), 0 = off (default: 0)\n";
}

std::string inputLimitOptionsHelp() {
  char text[400];
  std::snprintf(text, sizeof(text),
                "  -max_points N            refuse an input scan of more than N points, before reading it whole\n"
                "                           (default: %llu)\n",
                static_cast<unsigned long long>(io::kMaxCloudPoints));
  return text;
}

std::uint64_t maxPointsFrom(const Arguments& args) {
  if (!args.has("max_points")) return io::kMaxCloudPoints;
  const std::string text = args.text("max_points", "");
  char* end = nullptr;
  errno = 0;
  const unsigned long long value = std::strtoull(text.c_str(), &end, 10);
  if (text.empty() || text[0] == '-' || *end != '\0' || errno == ERANGE || value == 0) {
    throw std::invalid_argument("option -max_points: '" + text + "' is not a positive whole number of points");
  }
  return value;
}

DensifierConfig checkedDensifyOptions(const Arguments& args) {
  maxPointsFrom(args);
  outputOptionsFrom(args);
  if (args.has("image_size")) {
    int width = 0;
    int height = 0;
    parseImageSize(args.text("image_size", ""), width, height);
  }
  return configFrom(args, OptionScope::Cloud);
}

}  // namespace apps
}  // namespace lidar_sgm
