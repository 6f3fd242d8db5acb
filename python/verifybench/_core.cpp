// The `verifybench` Python module's compiled part (pybind11): the solver registry on numpy
// arrays, the synthetic generators and the dump readers. Arrays go in as (n, dim) float64
// (copied once into the column-major sets the solvers use) and come back as numpy arrays.
// Bad input raises ValueError (unknown names, shapes, non-finite values, bad parameters) or
// verifybench.InputError (a ValueError: a malformed file, naming file, line and field).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <chrono>
#include <limits>
#include <sstream>
#include <vector>
#include <cmath>
#include <optional>
#include <string>
#include <variant>

#include "acceptance/calibration.hpp"
#ifdef VERIFYBENCH_HAVE_DENSE_CHECK
#include "acceptance/dense_check.hpp"
#endif
#include "acceptance/prior_gate.hpp"
#include "acceptance/verify.hpp"
#include "core/transform.hpp"
#include "core/errors.hpp"
#include "core/suggest.hpp"
#include "datasets/dump_format.hpp"
#include "generators/synthetic.hpp"
#include "harness/builtin.hpp"
#include "solvers/registry.hpp"
#include "verifybench/version.hpp"

namespace py = pybind11;
namespace vb = verifybench;

namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// (n, dim) rows -> dim x n columns; names the argument, row and column of a bad value.
template <int Dim>
Eigen::Matrix<double, Dim, Eigen::Dynamic> columns(const Array& a, const char* name) {
  const auto r = a.unchecked<2>();
  Eigen::Matrix<double, Dim, Eigen::Dynamic> m(Dim, r.shape(0));
  for (py::ssize_t i = 0; i < r.shape(0); ++i) {
    for (int d = 0; d < Dim; ++d) {
      const double v = r(i, d);
      if (!std::isfinite(v)) {
        throw std::invalid_argument(std::string(name) + "[" + std::to_string(i) + ", " +
                                    std::to_string(d) + "] = " + std::to_string(v) +
                                    ": not a finite number");
      }
      m(d, i) = v;
    }
  }
  return m;
}

int dimension_of(const Array& src, const Array& dst) {
  if (src.ndim() != 2 || dst.ndim() != 2) {
    throw std::invalid_argument("src and dst must be 2-D arrays of shape (n, 2) or (n, 3); got " +
                                std::to_string(src.ndim()) + "-D and " +
                                std::to_string(dst.ndim()) + "-D");
  }
  if (src.shape(0) != dst.shape(0) || src.shape(1) != dst.shape(1)) {
    throw std::invalid_argument("src has shape (" + std::to_string(src.shape(0)) + ", " +
                                std::to_string(src.shape(1)) + "), dst (" +
                                std::to_string(dst.shape(0)) + ", " + std::to_string(dst.shape(1)) +
                                "): they must match");
  }
  if (src.shape(1) != 2 && src.shape(1) != 3) {
    throw std::invalid_argument("points have " + std::to_string(src.shape(1)) +
                                " columns: 2 (SE(2)) or 3 (SE(3)) expected");
  }
  if (src.shape(0) == 0) throw std::invalid_argument("src and dst are empty");
  return static_cast<int>(src.shape(1));
}

template <int Dim>
py::array_t<double> matrix(const vb::Rigid<Dim>& T) {
  py::array_t<double> out({Dim + 1, Dim + 1});
  auto w = out.mutable_unchecked<2>();
  const Eigen::Matrix<double, Dim + 1, Dim + 1> M = T.matrix();
  for (int i = 0; i <= Dim; ++i)
    for (int j = 0; j <= Dim; ++j) w(i, j) = M(i, j);
  return out;
}

template <int Dim>
py::array_t<double> rows(const Eigen::Matrix<double, Dim, Eigen::Dynamic>& m) {
  py::array_t<double> out({static_cast<py::ssize_t>(m.cols()), static_cast<py::ssize_t>(Dim)});
  auto w = out.mutable_unchecked<2>();
  for (Eigen::Index i = 0; i < m.cols(); ++i)
    for (int d = 0; d < Dim; ++d) w(i, d) = m(d, i);
  return out;
}

/// The pose prior of solve(): prior_T a (dim+1) x (dim+1) motion (checked as published_rigid
/// checks a file's), prior_cov the dof x dof covariance of its left perturbation; both or neither.
template <int Dim>
std::optional<vb::PosePrior<Dim>> pose_prior(const std::optional<Array>& T,
                                             const std::optional<Array>& cov) {
  if (!T && !cov) return std::nullopt;
  if (!T || !cov) throw std::invalid_argument("prior_T and prior_cov come together");
  constexpr int kDof = vb::kPoseDof<Dim>;
  if (T->ndim() != 2 || T->shape(0) != Dim + 1 || T->shape(1) != Dim + 1) {
    throw std::invalid_argument("prior_T must be a " + std::to_string(Dim + 1) + " x " +
                                std::to_string(Dim + 1) + " matrix");
  }
  if (cov->ndim() != 2 || cov->shape(0) != kDof || cov->shape(1) != kDof) {
    throw std::invalid_argument("prior_cov must be a " + std::to_string(kDof) + " x " +
                                std::to_string(kDof) + " matrix");
  }
  Eigen::Matrix<double, Dim + 1, Dim + 1> M;
  for (int i = 0; i <= Dim; ++i)
    for (int j = 0; j <= Dim; ++j) M(i, j) = T->at(i, j);
  vb::PosePrior<Dim> prior;
  prior.T_target_source = vb::published_rigid<Dim>(M, "prior_T").T;
  for (int i = 0; i < kDof; ++i)
    for (int j = 0; j < kDof; ++j) prior.covariance(i, j) = cov->at(i, j);
  return prior;  // the covariance is checked by validate(correspondences)
}

/// What solve() takes as keywords: the solver's settings and the accept rule's, read through one
/// table of the CLI's rows (solvers/params.hpp, acceptance/accept_params.hpp).
struct Settings {
  vb::SolverParams solver;
  vb::AcceptParams accept;
#ifdef VERIFYBENCH_HAVE_DENSE_CHECK
  vb::DenseCheckParams dense;  ///< with source_cloud / target_cloud
#endif
};
/// An (n, 3) array of points as a cloud for the dense check; a ValueError names a bad one.
std::vector<Eigen::Vector3f> cloud_of(const Array& a, const char* what) {
  if (a.ndim() != 2 || a.shape(1) != 3 || a.shape(0) < 1) {
    throw std::invalid_argument(std::string(what) + " must be an (n, 3) array with n >= 1");
  }
  const auto v = a.unchecked<2>();
  std::vector<Eigen::Vector3f> out;
  out.reserve(static_cast<std::size_t>(a.shape(0)));
  for (py::ssize_t i = 0; i < v.shape(0); ++i) {
    const Eigen::Vector3d p(v(i, 0), v(i, 1), v(i, 2));
    if (!p.allFinite()) {
      throw std::invalid_argument(std::string(what) + "[" + std::to_string(i) + "] is not finite");
    }
    out.push_back(p.cast<float>());
  }
  return out;
}

struct Clouds {
  std::optional<Array> source, target;
};

template <int Dim>
py::dict solve_dim(const std::string& name, const Array& src, const Array& dst,
                   const std::optional<Array>& scores, const std::optional<Array>& prior_T,
                   const std::optional<Array>& prior_cov, const Settings& settings,
                   const Clouds& clouds) {
  const vb::SolverParams& params = settings.solver;
  vb::AcceptParams accept = settings.accept;
  if (clouds.source.has_value() != clouds.target.has_value()) {
    throw std::invalid_argument("source_cloud and target_cloud come together");
  }
#ifdef VERIFYBENCH_HAVE_DENSE_CHECK
  std::vector<Eigen::Vector3f> source_cloud, target_cloud;
  if (clouds.source) {
    source_cloud = cloud_of(*clouds.source, "source_cloud");
    target_cloud = cloud_of(*clouds.target, "target_cloud");
  }
  // With clouds the dense check decides and the runner-up test is off unless asked (as in `run`).
  accept.resolve_runner_up(!source_cloud.empty() && settings.dense.min_overlap_for(accept.rule) > 0.0);
#else
  if (clouds.source) {
    throw std::invalid_argument("source_cloud: this build has no dense check (no front end)");
  }
#endif
  vb::Correspondences<Dim> corr;
  corr.prior = pose_prior<Dim>(prior_T, prior_cov);
  corr.source = columns<Dim>(src, "src");
  corr.target = columns<Dim>(dst, "dst");
  if (scores) {
    if (scores->ndim() != 1 || scores->shape(0) != src.shape(0)) {
      throw std::invalid_argument("scores must be a 1-D array of n = " +
                                  std::to_string(src.shape(0)) + " values");
    }
    const auto s = scores->unchecked<1>();
    for (py::ssize_t i = 0; i < s.shape(0); ++i) corr.score.push_back(s(i));
  }
  vb::validate(corr);
  const auto solver = vb::SolverRegistry::create(name);
  vb::Verification<Dim> v;
  {
    py::gil_scoped_release unlocked;  // other Python threads run while the C++ search does
    v = vb::verify(*solver, corr, params, accept);
  }
  py::object dense = py::none();
#ifdef VERIFYBENCH_HAVE_DENSE_CHECK
  // The dense check where the clouds are given (acceptance/dense_check.hpp), as `run` does it on a
  // dump's kept clouds: on a pair the rule accepted, at the rule's threshold.
  const double min_overlap = settings.dense.min_overlap_for(accept.rule);
  if (!source_cloud.empty() && v.result.accepted && min_overlap > 0.0) {
    const vb::Rigid<3> T = vb::lift_planar(v.result.T_target_source);
    vb::DenseCheck d;
    {
      py::gil_scoped_release unlocked;
      d = vb::dense_check(source_cloud, target_cloud, T, settings.dense);
    }
    py::dict check;
    check["overlap"] = d.overlap;
    check["icp_converged"] = d.icp.converged;
    check["icp_fitness_m2"] = d.icp.fitness;
    check["ms"] = d.ms;
    check["T_refined"] = matrix<3>(d.icp.T_target_source);
    dense = check;
    if (!(d.overlap > min_overlap)) {
      v.result.accepted = false;
      if (v.result.status == vb::Status::ok) v.result.status = vb::Status::rejected;
    }
  }
#endif
  const vb::Result<Dim>& result = v.result;
  const std::optional<vb::Calibration>& calibration = v.calibration;
  const double ms = v.solve_ms;
  if (result.status == vb::Status::error) throw std::invalid_argument(name + ": " + result.message);
  py::dict out;
  out["solver"] = name;
  out["dim"] = Dim;
  out["n"] = static_cast<int>(corr.size());
  out["inliers"] = py::array_t<long long>(static_cast<py::ssize_t>(result.inliers.size()),
                                          std::vector<long long>(result.inliers.begin(),
                                                                 result.inliers.end()).data());
  out["T"] = matrix<Dim>(result.T_target_source);
  out["accepted"] = result.accepted;
  out["status"] = vb::to_string(result.status);
  out["accept_rule"] = vb::to_string(v.rule);
  out["time_ms"] = ms;
  out["graph_ms"] = result.times.graph_ms;
  out["search_ms"] = result.times.search_ms;
  out["fit_ms"] = result.times.fit_ms;
  out["branch_nodes"] = result.counters.branch_nodes;
  out["iterations"] = result.counters.iterations;
  out["omega_upper_bound"] =
      result.omega_upper_bound ? py::object(py::int_(*result.omega_upper_bound)) : py::object(py::none());
  out["p_value"] = calibration ? py::object(py::float_(calibration->p_value)) : py::object(py::none());
  out["p_value_range"] =
      calibration ? py::object(py::make_tuple(calibration->p_value_low, calibration->p_value_high))
                  : py::object(py::none());
  out["null_threshold"] =
      calibration ? py::object(py::int_(calibration->threshold)) : py::object(py::none());
  out["calibration_ms"] =
      (calibration ? calibration->ms : 0.0) + (v.runner_up ? v.runner_up->ms : 0.0);
  out["prior_d2"] = v.prior_d2 ? py::object(py::float_(*v.prior_d2)) : py::object(py::none());
  out["null_screened"] = calibration ? calibration->screened : false;
  const auto& u = v.runner_up;  // the test ran: a pair the rest of the rule accepted
  out["provisional"] = (calibration && calibration->budget_exhausted) ||
                       (u && u->time_limit && !u->ambiguous);
  out["runner_up"] = u ? py::object(py::int_(u->score)) : py::object(py::none());
  out["runner_up_p"] =  // None also where it was not calibrated (runner_up.hpp)
      u && !std::isnan(u->p_value) ? py::object(py::float_(u->p_value)) : py::object(py::none());
  out["runner_up_separation"] = u ? py::object(py::float_(u->separation)) : py::object(py::none());
  out["runner_up_ambiguous"] = u ? u->ambiguous : false;
  out["runner_up_rivals"] = u ? py::object(py::int_(u->rivals)) : py::object(py::none());
  out["runner_up_support"] = u ? py::object(py::int_(u->rival_support)) : py::object(py::none());
  out["dense_check"] = dense;
  return out;
}

using SettingRow = vb::ParamRow<Settings>;

std::vector<SettingRow> make_setting_rows() {
  const std::vector<vb::ParamField> solver = vb::solver_param_rows();
  const auto common = static_cast<std::ptrdiff_t>(vb::common_param_family().fields.size());
  // The CLI's --help order: the common rows, the accept rule's, then every family's.
  std::vector<SettingRow> rows = vb::lift_rows(
      std::vector<vb::ParamField>(solver.begin(), solver.begin() + common), &Settings::solver);
  for (auto& r : vb::lift_rows(vb::accept_param_rows(), &Settings::accept)) rows.push_back(r);
#ifdef VERIFYBENCH_HAVE_DENSE_CHECK
  for (auto& r : vb::lift_rows(vb::dense_check_param_rows(), &Settings::dense)) rows.push_back(r);
#endif
  for (auto& r : vb::lift_rows(std::vector<vb::ParamField>(solver.begin() + common, solver.end()),
                               &Settings::solver)) {
    rows.push_back(r);
  }
  return rows;
}

/// The table, built once (solve() reads every call's keywords through it).
const std::vector<SettingRow>& setting_rows() {
  static const std::vector<SettingRow> rows = make_setting_rows();
  return rows;
}

/// Keywords read onto `p` by the same rows as the CLI's options (so the defaults, names and ranges
/// are the CLI's): an unknown keyword is a TypeError with the nearest name, a bad value a
/// ValueError naming it.
template <class P>
void read_keywords(const std::vector<vb::ParamRow<P>>& rows, const py::kwargs& given, P& p,
                   const std::string& function, const std::string& listing) {
  using Row = vb::ParamRow<P>;
  std::vector<bool> seen(rows.size(), false);
  for (const auto& item : given) {
    const std::string key = py::str(item.first);
    std::size_t k = 0;
    while (k < rows.size() && rows[k].keyword() != key) ++k;
    if (k == rows.size()) {
      std::vector<std::string> keywords;
      for (const auto& r : rows) keywords.push_back(r.keyword());
      const std::string best = vb::nearest_name(key, keywords);
      throw py::type_error(function + "(): unknown setting '" + key + "'" +
                           (best.empty() ? "" : " (did you mean '" + best + "'?)") + "; " +
                           listing + " lists them");
    }
    seen[k] = true;
    const Row& r = rows[k];
    const py::handle v = item.second;
    using K = typename Row::Kind;
    auto out_of_range = [&](double x) {
      std::ostringstream msg;
      msg << key << " = " << x << " is invalid; expected "
          << (r.expected.empty() ? "a value in " + r.range() : r.expected);
      throw std::invalid_argument(msg.str());
    };
    switch (r.kind) {
      case K::text:
        if (!py::isinstance<py::str>(v)) throw py::type_error(key + " must be a str");
        try {
          r.set_text(p, v.cast<std::string>());
        } catch (const std::invalid_argument& e) {
          throw std::invalid_argument(key + ": " + e.what());
        }
        break;
      case K::flag:
        if (!py::isinstance<py::bool_>(v)) throw py::type_error(key + " must be a bool");
        r.set(p, v.cast<bool>() ? 1.0 : 0.0);
        break;
      case K::integer: {
        if (py::isinstance<py::bool_>(v) || !py::isinstance<py::int_>(v)) {
          throw py::type_error(key + " must be an int");
        }
        const double x = static_cast<double>(v.cast<long long>());
        if (x < r.min || x > r.max) out_of_range(x);
        r.set(p, x);
        break;
      }
      case K::real: {
        if (py::isinstance<py::bool_>(v) || !(py::isinstance<py::float_>(v) || py::isinstance<py::int_>(v))) {
          throw py::type_error(key + " must be a number");
        }
        const double x = v.cast<double>();
        const bool infinite = r.infinite_ok && x == std::numeric_limits<double>::infinity();
        if (!infinite && !(std::isfinite(x) && x >= r.min && x <= r.max)) out_of_range(x);
        r.set(p, x);
        break;
      }
    }
  }
  for (std::size_t k = 0; k < rows.size(); ++k) {
    if (!seen[k] && rows[k].when_absent) rows[k].when_absent(p);
  }
}

Settings settings_from(const py::kwargs& given) {
  Settings p;
#ifdef VERIFYBENCH_HAVE_DENSE_CHECK
  p.dense.clouds = vb::DenseCheckParams::Clouds::scans;  // two scans, as a dump keeps them
#endif
  read_keywords(setting_rows(), given, p, "solve", "verifybench.settings()");
  return p;
}

py::dict solve(const std::string& name, const Array& src, const Array& dst,
               const std::optional<Array>& scores, const std::optional<Array>& prior_T,
               const std::optional<Array>& prior_cov, const std::optional<Array>& source_cloud,
               const std::optional<Array>& target_cloud, std::uint64_t seed,
               const py::kwargs& settings) {
  const int dim = dimension_of(src, dst);
  Settings s = settings_from(settings);
  s.solver.seed = seed;
  s.solver.validate();
  s.accept.validate();
#ifdef VERIFYBENCH_HAVE_DENSE_CHECK
  s.dense.validate();
#endif
  const Clouds clouds{source_cloud, target_cloud};
  return dim == 2 ? solve_dim<2>(name, src, dst, scores, prior_T, prior_cov, s, clouds)
                  : solve_dim<3>(name, src, dst, scores, prior_T, prior_cov, s, clouds);
}

/// Rows as Python dicts: keyword, CLI option, report key, kind, default (of `defaults`), range, help.
template <class P>
py::list rows_list(const std::vector<vb::ParamRow<P>>& rows, const P& defaults) {
  py::list out;
  for (const vb::ParamRow<P>& r : rows) {
    py::dict d;
    using K = typename vb::ParamRow<P>::Kind;
    d["keyword"] = r.keyword();
    d["option"] = "--" + r.option;
    d["key"] = r.key;
    d["kind"] = r.kind == K::real ? "real" : r.kind == K::integer ? "integer"
                : r.kind == K::flag ? "flag" : "text";
    if (!r.default_note.empty()) {
      d["default"] = r.default_note;
    } else if (r.kind == K::text) {
      d["default"] = r.get_text(defaults);
    } else if (r.kind == K::flag) {
      d["default"] = r.get(defaults) != 0.0;
    } else if (r.kind == K::integer) {
      d["default"] = static_cast<long long>(r.get(defaults));
    } else {
      d["default"] = r.get(defaults);
    }
    d["min"] = r.kind == K::real || r.kind == K::integer ? py::object(py::float_(r.min)) : py::object(py::none());
    d["max"] = r.kind == K::real || r.kind == K::integer ? py::object(py::float_(r.max)) : py::object(py::none());
    d["help"] = r.help;
    out.append(d);
  }
  return out;
}

/// Every setting solve() takes.
py::list settings_list() { return rows_list(setting_rows(), Settings{}); }

/// Every shape setting synthetic() takes (sweep's generator options).
py::list generator_settings_list() {
  return rows_list(vb::synthetic_shape_rows(), vb::SyntheticParams{});
}

template <int Dim>
py::dict set_dict(const vb::LabeledSet<Dim>& s) {
  py::dict out;
  out["dim"] = Dim;
  out["src"] = rows<Dim>(s.corr.source);
  out["dst"] = rows<Dim>(s.corr.target);
  out["scores"] = s.corr.score.empty()
                      ? py::object(py::none())
                      : py::object(py::array_t<double>(static_cast<py::ssize_t>(s.corr.score.size()),
                                                       s.corr.score.data()));
  out["labels"] = s.truth.labels.empty()
                      ? py::object(py::none())
                      : py::object(py::array_t<std::uint8_t>(static_cast<py::ssize_t>(s.truth.labels.size()),
                                                             s.truth.labels.data()));
  out["T"] = s.truth.T_target_source ? py::object(matrix<Dim>(*s.truth.T_target_source))
                                     : py::object(py::none());
  out["positive"] = s.truth.positive ? py::object(py::bool_(*s.truth.positive)) : py::object(py::none());
  return out;
}

/// synthetic()'s pose prior: per-axis sigmas drawn around the truth, as sweep's --prior-* options.
struct PriorSigmas {
  double rot_deg = 0.0, trans = 0.0;
};

template <int Dim>
py::dict synthetic_dict(vb::LabeledSet<Dim> set, const PriorSigmas& prior, std::uint64_t seed) {
  if (prior.rot_deg > 0.0) {
    vb::add_pose_prior(set, prior.rot_deg * M_PI / 180.0, prior.trans, seed);
  }
  py::dict out = set_dict<Dim>(set);
  out["prior_T"] = set.corr.prior ? py::object(matrix<Dim>(set.corr.prior->T_target_source))
                                  : py::object(py::none());
  if (set.corr.prior) {
    const auto& cov = set.corr.prior->covariance;
    py::array_t<double> c({static_cast<py::ssize_t>(cov.rows()), static_cast<py::ssize_t>(cov.cols())});
    for (Eigen::Index i = 0; i < cov.rows(); ++i)
      for (Eigen::Index j = 0; j < cov.cols(); ++j) c.mutable_at(i, j) = cov(i, j);
    out["prior_cov"] = c;
  } else {
    out["prior_cov"] = py::none();
  }
  return out;
}

py::dict synthetic(int n, double outliers, double noise, int dim, std::uint64_t seed,
                   const std::string& kind, double extent, bool negative, const PriorSigmas& prior,
                   const py::kwargs& shape) {
  if ((prior.rot_deg > 0.0) != (prior.trans > 0.0) || !(prior.rot_deg >= 0.0) ||
      !(prior.trans >= 0.0)) {
    throw std::invalid_argument("prior_rot_deg and prior_trans: both > 0 or both 0");
  }
  vb::SyntheticParams p;
  read_keywords(vb::synthetic_shape_rows(), shape, p, "synthetic",
                "verifybench.generator_settings()");
  p.n = n;
  p.outlier_ratio = outliers;
  p.noise = noise;
  p.seed = seed;
  p.kind = kind;
  p.extent = extent;
  p.max_translation = extent / 2;
  p.negative = negative;
  p.validate();
  if (dim == 2) return synthetic_dict<2>(vb::make_synthetic<2>(p), prior, seed);
  if (dim == 3) return synthetic_dict<3>(vb::make_synthetic<3>(p), prior, seed);
  throw std::invalid_argument("dim = " + std::to_string(dim) + ": 2 or 3 expected");
}

py::dict read_dump(const std::string& dir) {
  const vb::Dump dump = vb::read_dump(dir);
  py::dict out = std::visit([](const auto& s) { return set_dict(s); }, dump.set);
  out["label_threshold"] =
      dump.label_threshold ? py::object(py::float_(*dump.label_threshold)) : py::object(py::none());
  out["path"] = dir;
  // The clouds `extract --keep-clouds` kept, as (n, 3) arrays (solve()'s source_cloud and
  // target_cloud); None without.
  auto points = [](const std::vector<Eigen::Vector3f>& c) {
    py::array_t<double> a({static_cast<py::ssize_t>(c.size()), py::ssize_t{3}});
    auto v = a.mutable_unchecked<2>();
    for (std::size_t i = 0; i < c.size(); ++i)
      for (int d = 0; d < 3; ++d) v(static_cast<py::ssize_t>(i), d) = c[i][d];
    return a;
  };
  out["source_cloud"] = dump.clouds ? py::object(points(dump.clouds->source)) : py::object(py::none());
  out["target_cloud"] = dump.clouds ? py::object(points(dump.clouds->target)) : py::object(py::none());
  return out;
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "verifybench: geometric verification solvers, generators and dump readers";
  vb::register_builtin_solvers();
  py::register_exception<vb::InputError>(m, "InputError", PyExc_ValueError);
  m.attr("__version__") = vb::kVersion;
  m.attr("git_commit") = vb::kGitCommit;
  m.def("solvers", [] {
    std::vector<std::string> names;
    for (const auto& s : vb::SolverRegistry::list()) names.push_back(s.name);
    return names;
  }, "Names of the registered solvers (as `verifybench list` prints them).");
  m.def("generators", [] {
    std::vector<std::string> names;
    for (const auto& g : vb::list_generators()) names.push_back(g.name);
    return names;
  }, "Names of the synthetic generator kinds.");
  m.def("solve", &solve, py::arg("solver"), py::arg("src"), py::arg("dst"), py::kw_only(),
        py::arg("scores") = py::none(), py::arg("prior_T") = py::none(),
        py::arg("prior_cov") = py::none(), py::arg("source_cloud") = py::none(),
        py::arg("target_cloud") = py::none(), py::arg("seed") = 1,
        "Runs one registered solver on correspondences src[i] -> dst[i] ((n, 2) or (n, 3) arrays).\n"
        "Every solver setting of the CLI is a keyword (the option with '-' as '_': eps,\n"
        "inlier_threshold, accept, alpha, time_limit, ransac_iterations, ...; settings() lists\n"
        "them with their defaults, which are the CLI's: accept='pvalue').\n"
        "Returns a dict: inliers (ascending indices), T ((dim+1) x (dim+1), dst <- src), accepted,\n"
        "status, time_ms (the C++ call), graph_ms, search_ms, fit_ms, omega_upper_bound, p_value,\n"
        "provisional, runner_up, runner_up_p, runner_up_separation, runner_up_rivals,\n"
        "runner_up_support (None where the runner-up test did not run: it runs on a pair the rule\n"
        "accepted, by default at alpha without clouds and not with them), runner_up_ambiguous. prior_T, prior_cov: a pose prior (odometry's (dim+1) x (dim+1)\n"
        "guess and the 3 x 3 / 6 x 6 covariance of its left perturbation), both or neither; under\n"
        "'pvalue' a motion outside its chi-square gate at prior_gate is not accepted.\n"
        "source_cloud, target_cloud: the two scans ((k, 3) arrays, each in its own frame; read_dump()\n"
        "returns a dump's kept ones), both or neither: an accepted motion is refined by ICP and kept\n"
        "only when the clouds overlap by more than dense_overlap (the dense check of `run`);\n"
        "dense_check: its overlap, icp_converged, icp_fitness_m2, ms, T_refined (None where it did not run).");
  m.def("generator_settings", &generator_settings_list,
        "Every shape setting synthetic() takes, as `sweep` declares it: keyword, option, key, kind, "
        "default, min, max, help.");
  m.def("settings", &settings_list,
        "Every setting solve() takes, as the CLI declares it: keyword, option, key, kind, default, "
        "min, max, help.");
  m.def(
      "synthetic",
      [](int n, double outliers, double noise, int dim, std::uint64_t seed, const std::string& kind,
         double extent, bool negative, double prior_rot_deg, double prior_trans,
         const py::kwargs& shape) {
        return synthetic(n, outliers, noise, dim, seed, kind, extent, negative,
                         PriorSigmas{prior_rot_deg, prior_trans}, shape);
      },
      py::kw_only(), py::arg("n") = 500, py::arg("outliers") = 0.5, py::arg("noise") = 0.01,
      py::arg("dim") = 3, py::arg("seed") = 1, py::arg("kind") = "uniform",
      py::arg("extent") = 10.0, py::arg("negative") = false, py::arg("prior_rot_deg") = 0.0,
      py::arg("prior_trans") = 0.0,
      "A seeded synthetic set, as `sweep` draws it (the same kind and shape settings: every shape "
      "option of sweep is a keyword, '-' as '_', with sweep's default; generator_settings() lists "
      "them): dict of src, "
      "dst, labels (1 = inlier), T (the true motion), scores (None for score_separation < 0), "
      "positive, and prior_T / prior_cov (a pose prior drawn around the truth with per-axis sigmas "
      "prior_rot_deg [deg] and prior_trans [m], as sweep's --prior-rot-deg / --prior-trans; None "
      "without).");
  m.def("read_dump", &read_dump, py::arg("path"),
        "A correspondence dump folder (dump.json + matches.tsv, or corr.txt [label.txt] [GTmat.txt]); "
        "source_cloud / target_cloud: the clouds it kept (extract --keep-clouds), else None.");
}
