#pragma once
/// @file path_directions.hpp  The SGM path directions r of Eq. 1, in the order every backend
/// visits and sums them (the sums are of the same integers in any order, but the order is shared
/// so that the stages compare path by path).

namespace lidar_sgm {

/// A path direction r: L_r(p, d) recurses on L_r(p - r, .), r = (dx, dy).
struct PathDirection {
  int dx;
  int dy;
};

/// The paper's four paths first (left to right, right to left, top to bottom, bottom to top),
/// then the four diagonals that 8 paths add. The cuda backend keeps the same table in constant
/// memory (aggregation.cu).
inline constexpr PathDirection kPathDirections[8] = {{1, 0}, {-1, 0}, {0, 1},  {0, -1},
                                                     {1, 1}, {-1, 1}, {1, -1}, {-1, -1}};

}  // namespace lidar_sgm
