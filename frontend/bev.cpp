#include "frontend/bev.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace verifybench {

BevImage make_bev(const Cloud& cloud, const BevParams& params) {
  if (!(params.cell > 0.0) || !(params.range > params.cell) || !(params.min_fraction >= 0.0) ||
      !(params.min_fraction <= 1.0)) {
    std::ostringstream msg;
    msg << "bev: cell = " << params.cell << ", range = " << params.range
        << ", min_fraction = " << params.min_fraction
        << " are invalid; expected cell > 0, range > cell, min_fraction in [0, 1]";
    throw std::invalid_argument(msg.str());
  }
  // The image side, checked as a double before any conversion (a huge range / cell overflowed int):
  // at most kMaxBevSide cells a side (16384^2 counts = 1 GiB of ints).
  const double side = std::ceil(2.0 * params.range / params.cell);
  if (!(side <= kMaxBevSide)) {
    std::ostringstream msg;
    msg << "bev: range = " << params.range << " / cell = " << params.cell << " gives an image of "
        << side << " cells a side; at most " << kMaxBevSide;
    throw std::invalid_argument(msg.str());
  }
  BevImage img;
  img.cell = params.cell;
  img.origin = -params.range;
  img.size = static_cast<int>(std::ceil(2.0 * params.range / params.cell));
  img.counts.assign(static_cast<std::size_t>(img.size) * img.size, 0);
  for (const auto& p : cloud) {
    const double u = std::floor((p.x() - img.origin) / img.cell);
    const double v = std::floor((p.y() - img.origin) / img.cell);
    if (u < 0 || v < 0 || u >= img.size || v >= img.size) continue;
    ++img.counts[static_cast<std::size_t>(v) * img.size + static_cast<std::size_t>(u)];
  }
  const int peak = *std::max_element(img.counts.begin(), img.counts.end());
  img.pixels.assign(img.counts.size(), 0);
  if (peak == 0) return img;
  for (std::size_t k = 0; k < img.counts.size(); ++k) {
    const int c = img.counts[k];
    if (c < params.min_fraction * peak) continue;
    img.pixels[k] = static_cast<std::uint8_t>(std::lround(255.0 * c / peak));
  }
  return img;
}

}  // namespace verifybench
