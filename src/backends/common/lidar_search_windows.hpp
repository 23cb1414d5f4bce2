#pragma once
/// @file lidar_search_windows.hpp  The LiDAR gate of the disparity search (Parameters::gatedSearch).

#include "backends/common/search_windows.hpp"
#include "lidar_sgm/core/lidar_points.hpp"

namespace lidar_sgm {

/// The search window of every pixel from the LiDAR points around it, as tSGM narrows SGM's
/// search with a prior (disparity indices d of the range [0, numDisparities), disparity
/// minDisparity + d):
///  - the points within +-1 column and +-`rows` rows of the pixel (lidarCoverage's neighbourhood:
///    a pixel between two beams sees the points of both) bound the disparity to
///    [floor(min d_P) - margin, ceil(max d_P) + margin], min and max over those points (x16 values
///    divided by 16); both ends clamped into the range;
///  - that window widened upward to a multiple of 16 indices, then moved down as far as needed to
///    end inside the range (the range is a multiple of 16, so it always fits);
///  - a pixel without such a point, or whose points all lie outside the range, searches the full
///    range [0, numDisparities).
void lidarSearchWindows(const LidarPoints& points, int minDisparity, int numDisparities, int rows, int margin,
                        SearchWindows& windows);

/// lidarSearchWindows in its two passes, for a caller that splits the rows among threads:
/// prepareLidarSearchWindows once, then lidarSearchExtremes on row ranges that cover the frame,
/// then (after every one of them) lidarSearchWindowRows on row ranges that cover it. Within a
/// pass the row ranges are independent; the windows are those of lidarSearchWindows bit for bit.
void prepareLidarSearchWindows(const LidarPoints& points, int numDisparities, SearchWindows& windows);
/// Pass 1, rows y0 .. y1-1: the extremes of each pixel's points over +-1 column.
void lidarSearchExtremes(const LidarPoints& points, int y0, int y1, SearchWindows& windows);
/// Pass 2, rows y0 .. y1-1: the extremes over +-`rows` rows and the windows; `low16` and
/// `high16` are width int16 of the caller's scratch.
void lidarSearchWindowRows(int minDisparity, int rows, int margin, int y0, int y1, std::int16_t* low16,
                           std::int16_t* high16, SearchWindows& windows);
/// Pass 2's extremes of row y alone (the pixels' [low16, high16] over +-`rows` rows), for a
/// caller that applies the window rule itself (a SIMD backend).
void lidarSearchRowExtremes(int rows, int y, std::int16_t* low16, std::int16_t* high16, const SearchWindows& windows);

}  // namespace lidar_sgm
