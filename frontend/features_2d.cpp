// 2D front end: our bird's-eye-view density image, OpenCV's ORB keypoints and 256-bit descriptors,
// keypoints back to metric x-y through the image geometry.
#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <sstream>
#include <stdexcept>

#include "core/timer.hpp"
#include "frontend/features.hpp"

namespace verifybench {

Features features_2d(const Cloud& cloud, const Pipeline2dParams& p) {
  if (p.orb_features < 1) {
    throw std::invalid_argument("2D pipeline: orb_features = " + std::to_string(p.orb_features) +
                                " is invalid; expected an integer >= 1");
  }
  Features f;
  f.dim = 2;
  f.descriptors = BinaryDescriptors(256);
  f.counts["points"] = static_cast<double>(cloud.size());

  StopWatch bev_clock;
  const BevImage bev = make_bev(cloud, p.bev);
  f.ms["bev"] = bev_clock.ms();
  f.counts["bev_pixels"] = static_cast<double>(bev.pixels.size());
  int occupied = 0;
  for (auto px : bev.pixels) occupied += px > 0;
  f.counts["bev_occupied"] = occupied;

  StopWatch orb_clock;
  // One thread inside OpenCV for this call only (results must not depend on the thread count),
  // restored after, so the caller's OpenCV setting is left as it was.
  struct OneThread {
    int saved = cv::getNumThreads();
    OneThread() { cv::setNumThreads(1); }
    ~OneThread() { cv::setNumThreads(saved); }
  } one_thread;
  const cv::Mat image(bev.size, bev.size, CV_8UC1, const_cast<std::uint8_t*>(bev.pixels.data()));
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  cv::ORB::create(p.orb_features)->detectAndCompute(image, cv::noArray(), keypoints, descriptors);
  f.ms["orb"] = orb_clock.ms();
  f.counts["keypoints"] = static_cast<double>(keypoints.size());
  for (int k = 0; k < descriptors.rows; ++k) {
    auto* out = f.descriptors.add();
    const std::uint8_t* bytes = descriptors.ptr<std::uint8_t>(k);
    for (int b = 0; b < 32; ++b) out[b / 8] |= std::uint64_t{bytes[b]} << (8 * (b % 8));
    // OpenCV puts pixel centres at integer coordinates; ours are at + 0.5.
    const cv::Point2f& pt = keypoints[static_cast<std::size_t>(k)].pt;
    const Eigen::Vector2d xy = bev.metric(pt.x + 0.5, pt.y + 0.5);
    f.points.emplace_back(xy.x(), xy.y(), 0.0);
  }
  f.counts["descriptors"] = static_cast<double>(f.points.size());
  return f;
}

}  // namespace verifybench
