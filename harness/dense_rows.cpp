#include "harness/dense_rows.hpp"

#include <sstream>

#include "core/transform.hpp"

namespace verifybench {

namespace {

// The row's row-major (dim+1)^2 motion as a 3D one (a planar motion rotates about z).
template <int Dim>
Rigid<3> motion_of(const TrialRecord& r) {
  Eigen::Matrix<double, Dim + 1, Dim + 1> M;
  for (int i = 0; i <= Dim; ++i)
    for (int j = 0; j <= Dim; ++j) M(i, j) = r.T_target_source[i * (Dim + 1) + j];
  return lift_planar(Rigid<Dim>(M));
}

}  // namespace

void dense_check_rows(std::vector<TrialRecord>& rows, const DumpClouds& clouds,
                      const DenseCheckParams& params, AcceptParams::Rule rule,
                      const SuccessCriteria& criteria) {
  const double min_overlap = params.min_overlap_for(rule);
  if (!(min_overlap > 0.0)) return;
  for (auto& r : rows) {
    const std::size_t k = static_cast<std::size_t>(r.dim + 1);
    if (!r.accepted || r.T_target_source.size() != k * k) continue;
    const DenseCheck d = dense_check(clouds.source, clouds.target,
                                      r.dim == 2 ? motion_of<2>(r) : motion_of<3>(r), params);
    r.dense_overlap = d.overlap;
    r.dense_icp_converged = d.icp.converged;
    r.dense_icp_fitness = d.icp.converged ? d.icp.fitness : TrialRecord::kNaN;
    r.dense_ms = d.ms;
    r.dense_T_target_source.clear();
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) r.dense_T_target_source.push_back(d.icp.T_target_source(i, j));
    }
    if (d.overlap > min_overlap) continue;
    r.accepted = false;
    if (r.status == Status::ok) r.status = Status::rejected;
    if (criteria.requires_accepted && r.success) r.success = false;
    std::ostringstream msg;
    msg << "dense check: the clouds overlap by " << d.overlap << " after ICP, not above "
        << min_overlap;
    r.message = r.message.empty() ? msg.str() : r.message + "; " + msg.str();
  }
}

}  // namespace verifybench
