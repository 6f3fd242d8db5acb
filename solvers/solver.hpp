#pragma once
// The one virtual boundary: a solver takes correspondences (never ground truth) and returns the
// selected inliers, the motion and whether it would accept the pair as a loop closure.
#include <cstdint>
#include <string>
#include <vector>

#include "core/correspondences.hpp"

namespace verifybench {

struct SolverParams {
  double eps = 0.1;  ///< pair length tolerance of the correspondence graph, Eq. (1) [m]
  double inlier_threshold =
      0.1;              ///< residual ||T m - q|| under which a match is a consensus inlier [m]
  int min_inliers = 0;  ///< accept when |inliers| >= this; 0 = paper default (5 in 3D, 10 in 2D)
  double time_limit_s = 60.0;  ///< wall-clock limit of the search; best-so-far is returned past it
  std::uint64_t seed = 1;      ///< seed of every random draw a solver makes
  int ransac_iterations = 10000;     ///< RANSAC: fixed count, or the cap of the adaptive count
  bool ransac_adaptive = false;      ///< RANSAC: stop at k = log(1-p) / log(1-w^s)
  double ransac_confidence = 0.999;  ///< RANSAC: p of the adaptive count, in (0, 1)
  std::size_t max_graph_bytes = std::size_t{4} << 30;  ///< refuse larger correspondence graphs
  int threads =
      1;  ///< worker threads for graph construction (0 = all cores); results do not depend on it
  long long mac_max_cliques = 1000000;  ///< mac: stop enumerating maximal cliques after this many
  int mac_min_clique = 3;               ///< mac: smallest maximal clique that makes a hypothesis
  double jcbb_sigma = 0.0;  ///< jcbb: per-axis point noise sigma [m]; 0 = inlier_threshold / 3
  double jcbb_confidence = 0.95;  ///< jcbb: level of the chi-square gates, in (0, 1)

  /// Throws std::invalid_argument naming the field and the bad value.
  void validate() const;
  /// min_inliers with the paper's per-dimension default applied.
  int accept_threshold(int dim) const {
    return min_inliers > 0 ? min_inliers : (dim == 2 ? 10 : 5);
  }
  double jcbb_point_sigma() const { return jcbb_sigma > 0.0 ? jcbb_sigma : inlier_threshold / 3.0; }
};

enum class Status {
  ok,          ///< search completed and the pair is accepted
  rejected,    ///< search completed; fewer inliers than the accept threshold
  time_limit,  ///< limit reached; the result is the best found so far (accepted may still be true)
  error,       ///< the solver could not run (see message)
};
const char* to_string(Status s);

struct StageTimes {
  double graph_ms = 0.0;   ///< building the correspondence graph
  double search_ms = 0.0;  ///< clique search / hypothesis loop
  double fit_ms = 0.0;     ///< final least-squares fit
};

struct Counters {
  long long branch_nodes = 0;         ///< clique search nodes expanded
  long long iterations = 0;           ///< RANSAC hypotheses drawn (degenerate ones included)
  long long graph_edges = 0;          ///< edges of the correspondence graph
  long long local_optimisations = 0;  ///< LO-RANSAC inner optimisations run
};

template <int Dim>
struct Result {
  std::vector<int> inliers;  ///< selected correspondence indices, ascending
  Rigid<Dim> T_target_source = Rigid<Dim>::Identity();
  bool accepted = false;
  Status status = Status::error;
  std::string message;  ///< why, for Status::error
  StageTimes times;
  Counters counters;
};

class Solver {
 public:
  virtual ~Solver() = default;
  virtual Result<2> solve(const Correspondences<2>& corr, const SolverParams& params) const = 0;
  virtual Result<3> solve(const Correspondences<3>& corr, const SolverParams& params) const = 0;
};

/// Implements both virtual entry points with one template `Derived::run<Dim>`, so hot loops are
/// templated on the dimension; exceptions become Status::error with their message.
template <class Derived>
class SolverBase : public Solver {
 public:
  Result<2> solve(const Correspondences<2>& corr, const SolverParams& params) const override {
    return guarded<2>(corr, params);
  }
  Result<3> solve(const Correspondences<3>& corr, const SolverParams& params) const override {
    return guarded<3>(corr, params);
  }

 private:
  template <int Dim>
  Result<Dim> guarded(const Correspondences<Dim>& corr, const SolverParams& params) const {
    try {
      params.validate();
      validate(corr);
      return static_cast<const Derived&>(*this).template run<Dim>(corr, params);
    } catch (const std::exception& e) {
      Result<Dim> r;
      r.status = Status::error;
      r.message = e.what();
      return r;
    }
  }
};

/// Sets accepted and status from the inlier count and whether the search finished.
template <int Dim>
void decide(Result<Dim>& result, const SolverParams& params, bool finished) {
  result.accepted = static_cast<int>(result.inliers.size()) >= params.accept_threshold(Dim);
  result.status = !finished ? Status::time_limit : result.accepted ? Status::ok : Status::rejected;
}

}  // namespace verifybench
