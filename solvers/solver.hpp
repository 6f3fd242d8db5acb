#pragma once
// The one virtual boundary: a solver takes correspondences (never ground truth) and returns the
// selected inliers, the motion and whether it would accept the pair as a loop closure.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/correspondences.hpp"
#include "core/rigid_fit.hpp"
#include "core/status.hpp"
#include "solvers/params.hpp"

namespace verifybench {


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
  /// Clique solvers: a proven upper bound on the graph's clique number (the clique's size when
  /// proved optimal; above it when a limit stopped the search).
  std::optional<int> omega_upper_bound;
};

class Solver {
 public:
  virtual ~Solver() = default;
  virtual Result<2> solve(const Correspondences<2>& corr, const SolverParams& params) const = 0;
  virtual Result<3> solve(const Correspondences<3>& corr, const SolverParams& params) const = 0;
  /// An upper bound on the score (the selection's size) that `solve` can reach on `corr`, far
  /// cheaper than solving; nullopt when the solver has none, or none at this resolution worth
  /// its cost. `part_size`: the bounds split the set into parts of about this many
  /// correspondences and add up the parts' bounds (clique_number_bound): smaller parts cost less
  /// and bound more loosely. The calibrated rule screens the permuted sets with it before it
  /// solves them, coarse parts first (calibration.hpp).
  virtual std::optional<int> score_bound(const Correspondences<2>& corr, const SolverParams& params,
                                         int part_size) const = 0;
  virtual std::optional<int> score_bound(const Correspondences<3>& corr, const SolverParams& params,
                                         int part_size) const = 0;
  /// Whether several `solve` calls may run at once on different threads (no child processes, no
  /// state shared between calls); the calibrated rule then solves its null sets in parallel
  /// (calibration.hpp). Peers that fork or run OpenMP keep the default, no.
  virtual bool solves_concurrently() const { return false; }
  /// Whether `solve` searches for the largest consensus (a clique, sampled hypotheses) rather than
  /// converging from one start (GNC on all correspondences). The runner-up test needs a search to
  /// find the other motions a set holds: for a solver that has none it searches with `clique`
  /// (acceptance/runner_up.hpp).
  virtual bool searches() const { return true; }
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
  std::optional<int> score_bound(const Correspondences<2>& corr, const SolverParams& params,
                                 int part_size) const override {
    return guarded_bound<2>(corr, params, part_size);
  }
  std::optional<int> score_bound(const Correspondences<3>& corr, const SolverParams& params,
                                 int part_size) const override {
    return guarded_bound<3>(corr, params, part_size);
  }

  /// No bound; a solver that has one declares its own `bound<Dim>`, which hides this one.
  template <int Dim>
  std::optional<int> bound(const Correspondences<Dim>&, const SolverParams&, int) const {
    return std::nullopt;
  }

 private:
  template <int Dim>
  std::optional<int> guarded_bound(const Correspondences<Dim>& corr, const SolverParams& params,
                                   int part_size) const {
    try {
      if (part_size < 1) return std::nullopt;
      params.validate();
      validate(corr);
      return static_cast<const Derived&>(*this).template bound<Dim>(corr, params, part_size);
    } catch (const std::exception&) {
      return std::nullopt;  // no screen; the solve itself reports the problem
    }
  }

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

/// Sets accepted and status from the inlier count and whether the search finished. A selection
/// that does not pin down a motion (collinear or coincident points: pins_motion) is never
/// accepted, whatever its count.
template <int Dim>
void decide(Result<Dim>& result, const Correspondences<Dim>& corr, const SolverParams& params,
            bool finished) {
  result.accepted = static_cast<int>(result.inliers.size()) >= params.accept_threshold(Dim) &&
                    pins_motion(corr, result.inliers);
  result.status = !finished ? Status::time_limit : result.accepted ? Status::ok : Status::rejected;
}

}  // namespace verifybench
