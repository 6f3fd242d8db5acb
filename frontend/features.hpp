#pragma once
// The paper's two front ends, from one scan to keypoints with binary descriptors, and the
// registration papers' FPFH baseline with real-valued descriptors:
//   3D:   voxel grid -> ISS keypoints -> normals -> SHOT -> B-SHOT (352 bits)       (PCL)
//   2D:   bird's-eye-view density image -> ORB keypoints and descriptors (256 bits) (OpenCV)
//   FPFH: voxel grid (keypoints = voxel centroids) -> normals -> FPFH (33 bins)     (PCL)
// Stage counts and timings come back with the features, for the dump's provenance.
#include <map>
#include <string>

#include "frontend/bev.hpp"
#include "frontend/binary.hpp"

namespace verifybench {

struct Pipeline3dParams {
  double voxel = 0.5;           ///< voxel grid leaf [m]
  double salient_radius = 3.0;  ///< ISS salient radius [m]
  double non_max_radius = 2.0;  ///< ISS non-maximum suppression radius [m]
  double gamma21 = 0.975;       ///< ISS eigenvalue ratio thresholds
  double gamma32 = 0.975;
  int min_neighbors = 5;       ///< ISS minimum neighbours
  double normal_radius = 1.0;  ///< normal estimation radius [m]
  double shot_radius = 2.0;    ///< SHOT support radius [m]
};

struct Pipeline2dParams {
  BevParams bev;            ///< 0.5 m cells, 5% occupancy floor, 50 m range
  int orb_features = 1000;  ///< ORB: most keypoints kept
};

/// FPFH (Rusu et al. 2009) on every voxel centroid; radii 0 = the usual multiples of the voxel
/// (normals 2 V, FPFH 5 V, as FPFH-based registration papers set them).
struct PipelineFpfhParams {
  double voxel = 0.3;          ///< voxel grid leaf V [m]
  double normal_radius = 0.0;  ///< normal estimation radius [m]; 0 = 2 V
  double fpfh_radius = 0.0;    ///< FPFH support radius [m]; 0 = 5 V
  /// No keypoint (no descriptor) where the normal lies within this angle [deg] of the cloud's z
  /// axis: ground and ceilings, whose FPFH repeats everywhere and matches anywhere (0 = keep all).
  /// The support of the other descriptors keeps every point.
  double skip_horizontal_deg = 0.0;
};

/// Real-valued descriptors (FPFH: 33 floats), stored contiguously.
struct RealDescriptors {
  int dims = 0;
  std::vector<float> data;
  int size() const { return dims == 0 ? 0 : static_cast<int>(data.size()) / dims; }
  const float* row(int i) const { return data.data() + static_cast<std::size_t>(i) * dims; }
};

struct Features {
  int dim = 3;
  std::vector<Eigen::Vector3d> points;   ///< keypoints, metric (2D: z = 0)
  BinaryDescriptors descriptors;         ///< one per point (binary pipelines)
  RealDescriptors real;                  ///< one per point (FPFH); empty for binary pipelines
  std::map<std::string, double> counts;  ///< e.g. points, voxels, keypoints, descriptors
  std::map<std::string, double> ms;      ///< stage timings
};

/// Throws std::invalid_argument for a bad parameter (named, with the value).
Features features_3d(const Cloud& cloud, const Pipeline3dParams& params);
Features features_2d(const Cloud& cloud, const Pipeline2dParams& params);
Features features_fpfh(const Cloud& cloud, const PipelineFpfhParams& params);

}  // namespace verifybench
