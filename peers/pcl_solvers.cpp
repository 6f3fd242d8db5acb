// PCL's RANSACs as registry solvers (Debian libpcl-dev 1.13), each in two configurations:
//   pcl-ransac             CorrespondenceRejectorSampleConsensus, matched to ours: threshold
//                          = --inlier-threshold, up to --ransac-iterations (PCL's RANSAC is
//                          adaptive at p = 0.99), refine on
//   pcl-ransac-default     PCL's defaults: threshold 0.05 m, 1000 iterations, no refinement
//   pcl-prerejective       SampleConsensusPrerejective + TransformationEstimationSVD, matched:
//                          --ransac-iterations, similarity 0.9 (the edge check of lo-ransac and
//                          Open3D), max correspondence distance = --inlier-threshold, inlier
//                          fraction = our accept threshold / n
//   pcl-prerejective-default  PCL's defaults: 5000 iterations, similarity 0.6, inlier fraction 0
// Prerejective keeps the hypothesis of lowest mean inlier error among those with at least the
// inlier fraction, not the one with most inliers: a hypothesis explaining only its own sample
// very well can win.
// SampleConsensusPrerejective matches by features itself; it gets a feature that is the
// correspondence's index and k = 1, so that it draws exactly the given correspondences. It scores
// by nearest neighbours in the target cloud (not the given pairs), as PCL does.
// The reported inliers are the given correspondences the returned motion maps within
// --inlier-threshold, with no refit: the motion is PCL's own. PCL's samplers are seeded by PCL
// (RandomSampleConsensus: the fixed seed 12345; prerejective: std::rand, seeded here with --seed).
// Each runs in a child process killed at --time-limit (run_library_peer), where std::srand stays.
#include <pcl/common/transforms.h>
#include <pcl/console/print.h>
#include <pcl/point_types.h>
#include <pcl/registration/correspondence_rejection_sample_consensus.h>
#include <pcl/registration/sample_consensus_prerejective.h>
#include <pcl/registration/transformation_estimation_svd.h>

#include <algorithm>
#include <cstdlib>

#include "core/timer.hpp"
#include "peers/detail/embed.hpp"
#include "solvers/detail/consensus.hpp"
#include "solvers/registry.hpp"

namespace verifybench {

namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;

template <int Dim>
Cloud::Ptr cloud(const typename Correspondences<Dim>::Points& side) {
  Cloud::Ptr c(new Cloud);
  c->reserve(static_cast<std::size_t>(side.cols()));
  for (Eigen::Index i = 0; i < side.cols(); ++i) {
    const Eigen::Vector3f p = embed<Dim>(side, i).template cast<float>();
    c->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  }
  return c;
}

class PclRansac : public SolverBase<PclRansac> {
 public:
  explicit PclRansac(bool defaults) : defaults_(defaults) {}

  template <int Dim>
  Result<Dim> run(const Correspondences<Dim>& corr, const SolverParams& params) const {
    Result<Dim> result;
    pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
    run_library_peer<Dim>(
        corr, params, "PCL CorrespondenceRejectorSampleConsensus",
        [&] {
          pcl::Correspondences given;
          for (int i = 0; i < static_cast<int>(corr.size()); ++i) given.emplace_back(i, i, 0.0f);
          pcl::registration::CorrespondenceRejectorSampleConsensus<pcl::PointXYZ> rejector;
          rejector.setInputSource(cloud<Dim>(corr.source));
          rejector.setInputTarget(cloud<Dim>(corr.target));
          if (!defaults_) {
            rejector.setInlierThreshold(params.inlier_threshold);
            rejector.setMaximumIterations(params.ransac.iterations);
            rejector.setRefineModel(true);
          }
          pcl::Correspondences kept;
          if (corr.size() >= 3) rejector.getRemainingCorrespondences(given, kept);
          return Eigen::Matrix4d(rejector.getBestTransformation().template cast<double>());
        },
        result);
    return result;
  }

 private:
  bool defaults_;
};

class PclPrerejective : public SolverBase<PclPrerejective> {
 public:
  explicit PclPrerejective(bool defaults) : defaults_(defaults) {}

  template <int Dim>
  Result<Dim> run(const Correspondences<Dim>& corr, const SolverParams& params) const {
    using Feature = pcl::FPFHSignature33;  // index in bin 0: nearest feature = the given match
    Result<Dim> result;
    pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
    run_library_peer<Dim>(
        corr, params, "PCL SampleConsensusPrerejective",
        [&] {
          const auto n = static_cast<std::size_t>(corr.size());
          pcl::PointCloud<Feature>::Ptr features(new pcl::PointCloud<Feature>);
          features->resize(n);
          for (std::size_t i = 0; i < n; ++i) {
            std::fill(std::begin((*features)[i].histogram), std::end((*features)[i].histogram),
                      0.0f);
            (*features)[i].histogram[0] = static_cast<float>(i);
          }
          pcl::SampleConsensusPrerejective<pcl::PointXYZ, pcl::PointXYZ, Feature> align;
          align.setInputSource(cloud<Dim>(corr.source));
          align.setSourceFeatures(features);
          align.setInputTarget(cloud<Dim>(corr.target));
          align.setTargetFeatures(features);
          align.setTransformationEstimation(
              pcl::registration::TransformationEstimationSVD<pcl::PointXYZ, pcl::PointXYZ>::Ptr(
                  new pcl::registration::TransformationEstimationSVD<pcl::PointXYZ,
                                                                     pcl::PointXYZ>));
          align.setNumberOfSamples(3);
          align.setCorrespondenceRandomness(1);
          align.setMaxCorrespondenceDistance(params.inlier_threshold);
          if (!defaults_) {
            align.setMaximumIterations(params.ransac.iterations);
            align.setSimilarityThreshold(0.9f);
            // Our acceptance rule as its inlier fraction (PCL's default 0 admits any hypothesis).
            align.setInlierFraction(static_cast<float>(params.accept_threshold(Dim)) /
                                    static_cast<float>(std::max<std::size_t>(n, 1)));
          }
          Cloud aligned;
          Eigen::Matrix4d M = Eigen::Matrix4d::Identity();
          if (n >= 3) {
            std::srand(
                static_cast<unsigned>(params.seed));  // PCL draws from std::rand (in the child)
            align.align(aligned);
            if (align.hasConverged()) M = align.getFinalTransformation().template cast<double>();
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

void register_pcl_solvers() {
  SolverRegistry::add({"pcl-ransac",
                       "PCL CorrespondenceRejectorSampleConsensus, matched to ours (threshold, "
                       "--ransac-iterations cap, refine)",
                       [] { return std::make_unique<PclRansac>(false); }});
  SolverRegistry::add({"pcl-ransac-default",
                       "PCL CorrespondenceRejectorSampleConsensus with PCL's defaults (0.05 m, "
                       "1000 iterations)",
                       [] { return std::make_unique<PclRansac>(true); }});
  SolverRegistry::add({"pcl-prerejective",
                       "PCL SampleConsensusPrerejective + TransformationEstimationSVD on the given "
                       "matches, matched (--ransac-iterations, similarity 0.9)",
                       [] { return std::make_unique<PclPrerejective>(false); }});
  SolverRegistry::add({"pcl-prerejective-default",
                       "PCL SampleConsensusPrerejective with PCL's defaults (5000 iterations, "
                       "similarity 0.6)",
                       [] { return std::make_unique<PclPrerejective>(true); }});
}

}  // namespace verifybench
