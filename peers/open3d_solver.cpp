// Open3D's RegistrationRANSACBasedOnCorrespondence (Debian libopen3d-dev 0.16) as registry solvers:
//   open3d-ransac          matched to ours: --ransac-iterations cap, --ransac-confidence, the edge
//                          length checker at 0.9 (as lo-ransac), distance = --inlier-threshold
//   open3d-ransac-default  Open3D's defaults: 100,000 iterations, confidence 0.999, no checker
//                          (the distance has no default; --inlier-threshold)
// Open3D draws samples from one global generator inside an OpenMP loop, so its answer depends on
// the thread count; it is run single-threaded, seeded with --seed, so that it is reproducible.
// The reported inliers are the given correspondences its motion maps within --inlier-threshold,
// with no refit.
#include <omp.h>
#include <open3d/geometry/PointCloud.h>
#include <open3d/pipelines/registration/CorrespondenceChecker.h>
#include <open3d/pipelines/registration/Registration.h>
#include <open3d/utility/Logging.h>
#include <open3d/utility/Random.h>

#include "core/timer.hpp"
#include "peers/detail/embed.hpp"
#include "solvers/detail/consensus.hpp"
#include "solvers/registry.hpp"

namespace verifybench {

namespace {

namespace reg = open3d::pipelines::registration;

template <int Dim>
open3d::geometry::PointCloud cloud(const typename Correspondences<Dim>::Points& side) {
  open3d::geometry::PointCloud c;
  c.points_.reserve(static_cast<std::size_t>(side.cols()));
  for (Eigen::Index i = 0; i < side.cols(); ++i) c.points_.push_back(embed<Dim>(side, i));
  return c;
}

/// Restores OpenMP's thread count on every exit path.
class SingleThreaded {
 public:
  SingleThreaded() : saved_(omp_get_max_threads()) { omp_set_num_threads(1); }
  ~SingleThreaded() { omp_set_num_threads(saved_); }
  SingleThreaded(const SingleThreaded&) = delete;
  SingleThreaded& operator=(const SingleThreaded&) = delete;

 private:
  int saved_;
};

class Open3dRansac : public SolverBase<Open3dRansac> {
 public:
  explicit Open3dRansac(bool defaults) : defaults_(defaults) {}

  template <int Dim>
  Result<Dim> run(const Correspondences<Dim>& corr, const SolverParams& params) const {
    Result<Dim> result;
    open3d::utility::SetVerbosityLevel(open3d::utility::VerbosityLevel::Error);
    const auto source = cloud<Dim>(corr.source);
    const auto target = cloud<Dim>(corr.target);
    reg::CorrespondenceSet given;
    given.reserve(static_cast<std::size_t>(corr.size()));
    for (int i = 0; i < static_cast<int>(corr.size()); ++i) given.emplace_back(i, i);
    const reg::CorrespondenceCheckerBasedOnEdgeLength edges(0.9);
    std::vector<std::reference_wrapper<const reg::CorrespondenceChecker>> checkers;
    reg::RANSACConvergenceCriteria criteria;
    if (!defaults_) {
      checkers.push_back(edges);
      criteria = reg::RANSACConvergenceCriteria(params.ransac.iterations, params.ransac.confidence);
    }
    run_library_peer<Dim>(
        corr, params, "Open3D RegistrationRANSACBasedOnCorrespondence",
        [&] {
          Eigen::Matrix4d M = Eigen::Matrix4d::Identity();
          if (corr.size() >= 3) {
            SingleThreaded one;
            open3d::utility::random::Seed(static_cast<int>(params.seed & 0x7fffffff));
            const auto r = reg::RegistrationRANSACBasedOnCorrespondence(
                source, target, given, params.inlier_threshold,
                reg::TransformationEstimationPointToPoint(false), 3, checkers, criteria);
            M = r.transformation_;
          }
          return M;
        },
        result);
    return result;
  }

 private:
  bool defaults_;
};

}  // namespace

void register_open3d_solvers() {
  SolverRegistry::add(
      {"open3d-ransac",
       "Open3D RegistrationRANSACBasedOnCorrespondence, matched (--ransac-iterations "
       "cap, --ransac-confidence, edge-length checker 0.9), single thread",
       [] { return std::make_unique<Open3dRansac>(false); }});
  SolverRegistry::add({"open3d-ransac-default",
                       "Open3D RegistrationRANSACBasedOnCorrespondence with Open3D's defaults "
                       "(100,000 iterations, confidence 0.999, no checker), single thread",
                       [] { return std::make_unique<Open3dRansac>(true); }});
}

}  // namespace verifybench
