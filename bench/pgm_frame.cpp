#include "pgm_frame.hpp"

#include <cctype>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <vector>

namespace lidar_sgm {
namespace bench {
namespace {

std::string sizeText(int width, int height) { return std::to_string(width) + "x" + std::to_string(height); }

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot be opened");
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// The header of a P5 file and where its raster starts.
struct PgmHeader {
  int width = 0;
  int height = 0;
  int maxval = 0;
  std::size_t rasterOffset = 0;
};

/// Reads the header's next decimal field, skipping whitespace and '#' comments (to the end of
/// the line) before it, as the PGM format allows.
int headerField(const std::string& bytes, std::size_t& pos, const char* name, const std::string& path) {
  for (;;) {
    while (pos < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[pos]))) ++pos;
    if (pos < bytes.size() && bytes[pos] == '#') {
      while (pos < bytes.size() && bytes[pos] != '\n' && bytes[pos] != '\r') ++pos;
      continue;
    }
    break;
  }
  long value = 0;
  const std::size_t start = pos;
  while (pos < bytes.size() && std::isdigit(static_cast<unsigned char>(bytes[pos]))) {
    value = value * 10 + (bytes[pos] - '0');
    if (value > 65535) throw std::runtime_error(path + ": PGM " + name + " is larger than 65535");
    ++pos;
  }
  if (pos == start) throw std::runtime_error(path + ": PGM header has no " + name);
  if (value < 1) throw std::runtime_error(path + ": PGM " + name + " is 0");
  return static_cast<int>(value);
}

PgmHeader parseHeader(const std::string& bytes, const std::string& path) {
  if (bytes.size() < 2 || bytes[0] != 'P' || bytes[1] != '5') {
    throw std::runtime_error(path + ": not a binary PGM (it does not start with P5)");
  }
  PgmHeader h;
  std::size_t pos = 2;
  h.width = headerField(bytes, pos, "width", path);
  h.height = headerField(bytes, pos, "height", path);
  h.maxval = headerField(bytes, pos, "maxval", path);
  // Exactly one whitespace character separates maxval from the raster.
  if (pos >= bytes.size() || !std::isspace(static_cast<unsigned char>(bytes[pos]))) {
    throw std::runtime_error(path + ": PGM header does not end with a whitespace after maxval");
  }
  h.rasterOffset = pos + 1;
  const std::size_t bytesPerSample = h.maxval < 256 ? 1 : 2;
  const std::size_t needed = static_cast<std::size_t>(h.width) * h.height * bytesPerSample;
  if (bytes.size() - h.rasterOffset < needed) {
    throw std::runtime_error(path + ": PGM raster is truncated (" + std::to_string(bytes.size() - h.rasterOffset) +
                             " bytes, " + sizeText(h.width, h.height) + " needs " + std::to_string(needed) + ")");
  }
  return h;
}

void checkSample(int value, const PgmHeader& h, int x, int y, const std::string& path) {
  if (value > h.maxval) {
    throw std::runtime_error(path + ": sample " + std::to_string(value) + " at (" + std::to_string(x) + ", " +
                             std::to_string(y) + ") exceeds maxval " + std::to_string(h.maxval));
  }
}

template <typename T>
void writeP5(const std::string& path, ImageView<const T> image, int maxval) {
  if (image.empty()) throw std::runtime_error(path + ": cannot write an empty image");
  std::ofstream out(path, std::ios::binary);
  if (!out) throw std::runtime_error(path + ": cannot be written");
  out << "P5\n" << image.width << ' ' << image.height << '\n' << maxval << '\n';
  std::vector<char> row(static_cast<std::size_t>(image.width) * sizeof(T));
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const unsigned value = image(x, y);
      if (sizeof(T) == 1) {
        row[static_cast<std::size_t>(x)] = static_cast<char>(value);
      } else {  // most significant byte first (the PGM format)
        row[2 * static_cast<std::size_t>(x)] = static_cast<char>(value >> 8);
        row[2 * static_cast<std::size_t>(x) + 1] = static_cast<char>(value & 0xffu);
      }
    }
    out.write(row.data(), static_cast<std::streamsize>(row.size()));
  }
  if (!out) throw std::runtime_error(path + ": writing failed");
}

std::string firstLine(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  return line;
}

void checkSize(int width, int height, const Frame& frame, const std::string& path) {
  if (width != frame.width() || height != frame.height()) {
    throw std::runtime_error(path + " is " + sizeText(width, height) + " but left.pgm is " +
                             sizeText(frame.width(), frame.height()));
  }
}

}  // namespace

Image<std::uint8_t> readPgm8(const std::string& path) {
  const std::string bytes = readFile(path);
  const PgmHeader h = parseHeader(bytes, path);
  if (h.maxval >= 256) {
    throw std::runtime_error(path + ": 16-bit PGM (maxval " + std::to_string(h.maxval) + ") where an 8-bit one is expected");
  }
  Image<std::uint8_t> image(h.width, h.height);
  const auto* raster = reinterpret_cast<const unsigned char*>(bytes.data() + h.rasterOffset);
  for (int y = 0; y < h.height; ++y) {
    for (int x = 0; x < h.width; ++x) {
      const int value = raster[static_cast<std::size_t>(y) * h.width + x];
      checkSample(value, h, x, y, path);
      image(x, y) = static_cast<std::uint8_t>(value);
    }
  }
  return image;
}

Image<std::uint16_t> readPgm16(const std::string& path) {
  const std::string bytes = readFile(path);
  const PgmHeader h = parseHeader(bytes, path);
  if (h.maxval < 256) {
    throw std::runtime_error(path + ": 8-bit PGM (maxval " + std::to_string(h.maxval) + ") where a 16-bit one is expected");
  }
  Image<std::uint16_t> image(h.width, h.height);
  const auto* raster = reinterpret_cast<const unsigned char*>(bytes.data() + h.rasterOffset);
  for (int y = 0; y < h.height; ++y) {
    for (int x = 0; x < h.width; ++x) {
      const std::size_t i = 2 * (static_cast<std::size_t>(y) * h.width + x);
      const int value = (raster[i] << 8) | raster[i + 1];
      checkSample(value, h, x, y, path);
      image(x, y) = static_cast<std::uint16_t>(value);
    }
  }
  return image;
}

void writePgm(const std::string& path, ImageView<const std::uint8_t> image) { writeP5(path, image, 255); }
void writePgm(const std::string& path, ImageView<const std::uint16_t> image) { writeP5(path, image, 65535); }

Frame readPgmFrame(const std::string& folder) {
  const std::filesystem::path dir(folder);
  if (!std::filesystem::is_directory(dir)) throw std::runtime_error(folder + ": no such frame folder");
  const std::string left = (dir / "left.pgm").string();
  const std::string right = (dir / "right.pgm").string();
  const std::string lidar = (dir / "lidar16.pgm").string();
  Frame frame;
  frame.left = readPgm8(left);
  frame.right = readPgm8(right);
  checkSize(frame.right.width(), frame.right.height(), frame, right);
  const Image<std::uint16_t> lidar16 = readPgm16(lidar);
  checkSize(lidar16.width(), lidar16.height(), frame, lidar);
  // LidarPoints reads int16 x16 disparities; 0 is "no point" for both.
  Image<std::int16_t> sparse(lidar16.width(), lidar16.height());
  for (int y = 0; y < sparse.height(); ++y) {
    for (int x = 0; x < sparse.width(); ++x) {
      const int d16 = lidar16(x, y);
      if (d16 > 32767) {
        throw std::runtime_error(lidar + ": x16 disparity " + std::to_string(d16) + " at (" + std::to_string(x) + ", " +
                                 std::to_string(y) + ") is above 32767 (2047.9 px)");
      }
      sparse(x, y) = static_cast<std::int16_t>(d16);
    }
  }
  frame.lidar = LidarPoints::fromDisparityImage(sparse.view());
  const std::filesystem::path sourceFile = dir / "source.txt";
  const std::string origin = std::filesystem::exists(sourceFile) ? firstLine(sourceFile.string()) : "";
  frame.source = "PGM frame folder" + (origin.empty() ? std::string() : ": " + origin);
  frame.files = {{"left", left}, {"right", right}, {"LiDAR", lidar}};
  return frame;
}

void writePgmFrame(const Frame& frame, const std::string& folder) {
  if (frame.left.empty() || frame.right.empty()) throw std::runtime_error("cannot export a frame without images");
  if (frame.lidar.width() != frame.width() || frame.lidar.height() != frame.height()) {
    throw std::runtime_error("cannot export a frame whose LiDAR is " +
                             sizeText(frame.lidar.width(), frame.lidar.height()) + " but its images are " +
                             sizeText(frame.width(), frame.height()));
  }
  Image<std::uint16_t> lidar16(frame.width(), frame.height(), 0);
  for (int y = 0; y < frame.height(); ++y) {
    for (int x = 0; x < frame.width(); ++x) {
      const int count = frame.lidar.count(x, y);
      if (count > 1) {
        throw std::runtime_error("cannot export the LiDAR: pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                                 ") has " + std::to_string(count) + " points, a PGM holds one");
      }
      if (count == 0) continue;
      const int d16 = *frame.lidar.begin(x, y);
      if (d16 < 1 || d16 > 32767) {
        throw std::runtime_error("cannot export the LiDAR: x16 disparity " + std::to_string(d16) + " at (" +
                                 std::to_string(x) + ", " + std::to_string(y) + ") is outside [1, 32767]");
      }
      lidar16(x, y) = static_cast<std::uint16_t>(d16);
    }
  }
  std::error_code error;
  std::filesystem::create_directories(folder, error);
  if (error) throw std::runtime_error(folder + ": cannot create the folder (" + error.message() + ")");
  const std::filesystem::path dir(folder);
  writePgm((dir / "left.pgm").string(), frame.left.view());
  writePgm((dir / "right.pgm").string(), frame.right.view());
  writePgm((dir / "lidar16.pgm").string(), lidar16.view());
  std::ofstream source(dir / "source.txt");
  source << frame.source << '\n';
  if (!source) throw std::runtime_error((dir / "source.txt").string() + ": cannot be written");
}

}  // namespace bench
}  // namespace lidar_sgm
