#pragma once
// Bird's-eye-view density image of a scan (the paper's 2D pipeline): the points' x-y counts on a
// grid of `cell` metres over [-range, range]^2 around the sensor, scaled so that the fullest cell
// is 255, and cells under min_fraction of that maximum set to 0.
#include <cstdint>
#include <vector>

#include "frontend/cloud_io.hpp"

namespace verifybench {

/// The largest bird's-eye-view image side make_bev() builds, in cells.
inline constexpr int kMaxBevSide = 16384;

struct BevParams {
  double cell = 0.5;           ///< metres per pixel, > 0
  double min_fraction = 0.05;  ///< cells below this fraction of the maximum count are dropped
  double range = 50.0;         ///< half side of the imaged square [m], > cell
};

struct BevImage {
  int size = 0;  ///< width = height [pixels]
  double cell = 0.5,
         origin = -50.0;             ///< pixel (u, v) covers x in origin + [u, u + 1) cell, y alike
  std::vector<std::uint8_t> pixels;  ///< row v (y) major: pixels[v * size + u]
  std::vector<int> counts;           ///< raw point counts per cell, same layout

  /// Metric x-y of a (sub)pixel position; pixel centres are at integer + 0.5.
  Eigen::Vector2d metric(double u, double v) const {
    return {origin + u * cell, origin + v * cell};
  }
};

/// Throws std::invalid_argument for bad parameters (named, with the value).
BevImage make_bev(const Cloud& cloud, const BevParams& params);

}  // namespace verifybench
