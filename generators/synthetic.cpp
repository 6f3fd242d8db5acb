#include "generators/synthetic.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <sstream>
#include <stdexcept>

#include "core/random.hpp"
#include "core/registry.hpp"

namespace verifybench {

namespace {

void require(bool ok, const char* field, double value, const char* expected) {
  if (ok) return;
  std::ostringstream msg;
  msg << "synthetic generator: " << field << " = " << value << " is invalid; expected " << expected;
  throw std::invalid_argument(msg.str());
}

template <int Dim>
Eigen::Matrix<double, Dim, Dim> random_rotation(std::mt19937_64& rng);

template <>
Eigen::Matrix2d random_rotation<2>(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  return Eigen::Rotation2Dd(angle(rng)).toRotationMatrix();
}

template <>
Eigen::Matrix3d random_rotation<3>(std::mt19937_64& rng) {
  // A normalised 4D Gaussian is a uniform unit quaternion, hence a uniform rotation.
  std::normal_distribution<double> g(0.0, 1.0);
  Eigen::Quaterniond q(g(rng), g(rng), g(rng), g(rng));
  return q.normalized().toRotationMatrix();
}

template <int Dim>
using Vec = Eigen::Matrix<double, Dim, 1>;

/// The draws every kind shares, in the order the original uniform generator made them.
template <int Dim>
struct Draws {
  explicit Draws(const SyntheticParams& p)
      : p(p), rng(p.seed), shift(-p.max_translation, p.max_translation) {}

  Vec<Dim> in_cube() {
    Vec<Dim> v;
    for (int d = 0; d < Dim; ++d) v(d) = p.extent * unit(rng);
    return v;
  }
  Vec<Dim> gaussian(double sigma) {
    Vec<Dim> v;
    for (int d = 0; d < Dim; ++d) v(d) = sigma * normal(rng);
    return v;
  }
  Vec<Dim> direction() {
    Vec<Dim> v = gaussian(1.0);
    while (v.norm() < 1e-9) v = gaussian(1.0);
    return v.normalized();
  }
  Rigid<Dim> motion() {
    Rigid<Dim> T = Rigid<Dim>::Identity();
    T.linear() = random_rotation<Dim>(rng);
    if constexpr (Dim == 3) {
      // Ground vehicles (Quatro's regime): yaw only, uniform; the same draws otherwise.
      if (p.planar_motion) {
        T.linear() = Eigen::Matrix3d::Identity();
        T.linear().template topLeftCorner<2, 2>() = random_rotation<2>(rng);
      }
    }
    for (int d = 0; d < Dim; ++d) T.translation()(d) = shift(rng);
    return T;
  }
  double uniform(double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng);
  }
  int index(int count) { return std::uniform_int_distribution<int>(0, count - 1)(rng); }

  const SyntheticParams& p;
  std::mt19937_64 rng;
  std::uniform_real_distribution<double> unit{-0.5, 0.5};
  std::uniform_real_distribution<double> shift;
  std::normal_distribution<double> normal{0.0, 1.0};
};

/// Angle of a^-1 b [rad].
template <int Dim>
double rotation_angle(const Rigid<Dim>& a, const Rigid<Dim>& b) {
  const Eigen::Matrix<double, Dim, Dim> R = a.linear().transpose() * b.linear();
  const double c = std::clamp((R.trace() - (Dim - 2)) / 2.0, -1.0, 1.0);
  return std::acos(c);
}

/// Shuffled labels: n - round(n * ratio) ones.
std::vector<std::uint8_t> draw_labels(const SyntheticParams& p, std::mt19937_64& rng) {
  const int outliers = static_cast<int>(std::lround(p.outlier_ratio * p.n));
  std::vector<std::uint8_t> labels(static_cast<std::size_t>(p.n), 0);
  std::fill(labels.begin(), labels.begin() + (p.n - outliers), 1);
  std::shuffle(labels.begin(), labels.end(), rng);
  return labels;
}

template <int Dim>
void put(LabeledSet<Dim>& set, int i, const Vec<Dim>& m, const Vec<Dim>& q) {
  set.corr.source.col(i) = m;
  set.corr.target.col(i) = q;
}

/// uniform, rigid-group, partial-overlap, heavy-tailed, anisotropic, near-true: source points in
/// the cube, inliers q = T m + noise, outliers by kind.
template <int Dim>
void fill_cube_kinds(const SyntheticParams& p, Draws<Dim>& draw, const Rigid<Dim>& T,
                     LabeledSet<Dim>& set) {
  const auto& labels = set.truth.labels;
  const int inliers = static_cast<int>(std::count(labels.begin(), labels.end(), 1));
  const int outliers = p.n - inliers;
  // rigid-group: the first `group` outliers (in index order) follow one wrong motion.
  const int group = p.kind == "rigid-group"
                        ? std::min(outliers, static_cast<int>(std::lround(p.group_ratio * inliers)))
                        : 0;
  Rigid<Dim> wrong = T;
  if (group > 0) {
    while (rotation_angle(wrong, T) < 0.5) wrong = draw.motion();  // at least ~30 deg apart
  }
  std::student_t_distribution<double> student(p.tail_dof);
  int grouped = 0;
  for (int i = 0; i < p.n; ++i) {
    Vec<Dim> m = draw.in_cube();
    Vec<Dim> q;
    if (labels[static_cast<std::size_t>(i)]) {
      if (p.kind == "partial-overlap") {  // inliers only in the overlapping slab x < x0
        m(0) = p.extent * (-0.5 + p.overlap * (m(0) / p.extent + 0.5));
      }
      q = T * m;
      if (p.kind == "heavy-tailed") {
        for (int d = 0; d < Dim; ++d) q(d) += p.noise * student(draw.rng);
      } else if (p.kind == "anisotropic") {
        // Range noise: sigma * anisotropy along the ray from the sensor (target origin).
        const Vec<Dim> ray = q.norm() > 1e-9 ? Vec<Dim>(q.normalized()) : Vec<Dim>::UnitX();
        const Vec<Dim> e = draw.gaussian(p.noise);
        q += e + (p.anisotropy - 1.0) * ray.dot(e) * ray;
      } else {
        for (int d = 0; d < Dim; ++d) q(d) += p.noise * draw.normal(draw.rng);
      }
    } else if (grouped < group) {
      ++grouped;
      q = wrong * m + draw.gaussian(p.noise);
    } else if (p.kind == "near-true") {
      q = T * m + draw.uniform(0.25 * p.near_radius, p.near_radius) * draw.direction();
    } else {
      q = T * draw.in_cube();  // an unrelated point of the same scene
    }
    put(set, i, m, q);
  }
}

/// repetitive: a corridor of identical pillars every grid_spacing along x; outliers match the same
/// spot of a pillar one or two steps further along, so each shift is a rigidly consistent wrong
/// group (a translation error of 1-2 steps).
template <int Dim>
void fill_repetitive(const SyntheticParams& p, Draws<Dim>& draw, const Rigid<Dim>& T,
                     LabeledSet<Dim>& set) {
  const int steps = std::max(1, static_cast<int>(std::floor(p.extent / p.grid_spacing)));
  for (int i = 0; i < p.n; ++i) {
    // Pillars every grid_spacing along x, each 0.4 steps thick; free across the corridor.
    Vec<Dim> m = draw.in_cube();
    m(0) = p.grid_spacing * (draw.index(steps + 1) - steps / 2 + draw.uniform(-0.2, 0.2));
    Vec<Dim> q;
    if (set.truth.labels[static_cast<std::size_t>(i)]) {
      q = T * m;
    } else {
      static constexpr int kShifts[] = {-2, -1, 1, 2};
      Vec<Dim> copy = m;
      copy(0) += p.grid_spacing * kShifts[draw.index(4)];
      q = T * copy;
    }
    put<Dim>(set, i, m, q + draw.gaussian(p.noise));
  }
}

/// bev-orb: keypoints of a bird's-eye-view image: corners along walls (line segments) of a local
/// map, both sides quantised to `cell`; outliers are half descriptor confusions within
/// near_radius, half unrelated keypoints on other walls.
void fill_bev_orb(const SyntheticParams& p, Draws<2>& draw, const Rigid<2>& T, LabeledSet<2>& set) {
  struct Wall {
    Vec<2> a, b;
  };
  std::vector<Wall> walls(static_cast<std::size_t>(std::max(4, p.n / 40)));
  for (auto& w : walls) {
    w.a = draw.in_cube();
    w.b = w.a + draw.uniform(0.1, 0.4) * p.extent * draw.direction();
  }
  auto on_wall = [&] {
    const Wall& w = walls[static_cast<std::size_t>(draw.index(static_cast<int>(walls.size())))];
    return Vec<2>(w.a + draw.uniform(0.0, 1.0) * (w.b - w.a));
  };
  auto quantise = [&](const Vec<2>& v) {
    return Vec<2>(((v.array() / p.cell).floor() + 0.5) * p.cell);
  };
  for (int i = 0; i < p.n; ++i) {
    const Vec<2> x = on_wall();
    Vec<2> q;
    if (set.truth.labels[static_cast<std::size_t>(i)]) {
      q = T * x + draw.gaussian(p.noise);
    } else if (draw.index(2) == 0) {
      q = T * x + draw.uniform(0.25 * p.near_radius, p.near_radius) * draw.direction();
    } else {
      q = T * on_wall();
    }
    put(set, i, quantise(x), quantise(q));
  }
}

// The kinds, in the order `verifybench list` shows them; each fills a set in 2D and/or 3D.
template <int Dim>
using Fill = void (*)(const SyntheticParams&, Draws<Dim>&, const Rigid<Dim>&, LabeledSet<Dim>&);

struct Kind {
  GeneratorInfo info;
  Fill<2> fill2;
  Fill<3> fill3;
};

const std::vector<Kind>& kinds() {
  static const std::vector<Kind> table = {
      {{"uniform", "outlier targets uniform in the scene; Gaussian noise on inliers", true, true},
       fill_cube_kinds<2>,
       fill_cube_kinds<3>},
      {{"rigid-group",
        "adds a rigidly consistent wrong group (--group-ratio x inliers) following a second motion",
        true, true},
       fill_cube_kinds<2>,
       fill_cube_kinds<3>},
      {{"repetitive",
        "corridor lattice (--grid-spacing); outliers match pillars 1-2 steps along, each shift a "
        "consistent wrong group",
        true, true},
       fill_repetitive<2>,
       fill_repetitive<3>},
      {{"partial-overlap", "inliers only in a slab of --overlap of the scene; outliers anywhere",
        true, true},
       fill_cube_kinds<2>,
       fill_cube_kinds<3>},
      {{"heavy-tailed", "Student-t noise on inliers (--tail-dof), uniform outliers", true, true},
       fill_cube_kinds<2>,
       fill_cube_kinds<3>},
      {{"anisotropic", "range noise --anisotropy x larger along the sensor ray, uniform outliers",
        true, true},
       fill_cube_kinds<2>,
       fill_cube_kinds<3>},
      {{"near-true", "outliers within --near-radius of the true match (descriptor confusions)",
        true, true},
       fill_cube_kinds<2>,
       fill_cube_kinds<3>},
      {{"bev-orb",
        "2D bird's-eye-view ORB-like matches: corners on walls, --cell quantisation, near and "
        "cross-wall confusions",
        true, false},
       fill_bev_orb,
       nullptr},
  };
  return table;
}

const Registry<GeneratorInfo>& generators() {
  static Registry<GeneratorInfo> registry("kind", Registry<GeneratorInfo>::Order::as_added);
  static std::once_flag once;
  std::call_once(once, [] {
    for (const Kind& k : kinds()) registry.add(k.info);
  });
  return registry;
}

}  // namespace

std::vector<GeneratorInfo> list_generators() { return generators().list(); }

const GeneratorInfo& find_generator(const std::string& kind) { return generators().get(kind); }

void SyntheticParams::validate() const {
  require(n >= 1, "n", n, "an integer >= 1");
  require(outlier_ratio >= 0.0 && outlier_ratio <= 1.0, "outlier_ratio", outlier_ratio,
          "a value in [0, 1]");
  require(noise >= 0.0 && std::isfinite(noise), "noise", noise, "a finite value >= 0");
  require(extent > 0.0 && std::isfinite(extent), "extent", extent, "a finite value > 0");
  require(max_translation >= 0.0 && std::isfinite(max_translation), "max_translation",
          max_translation, "a finite value >= 0");
  require(group_ratio > 0.0 && std::isfinite(group_ratio), "group_ratio", group_ratio,
          "a finite value > 0");
  require(grid_spacing > 0.0 && (kind != "repetitive" || grid_spacing <= extent), "grid_spacing",
          grid_spacing, "a value in (0, extent]");
  require(kind != "repetitive" || extent / grid_spacing <= 1e6, "grid_spacing", grid_spacing,
          "at least extent / 1e6 (at most a million pillars)");
  require(overlap > 0.0 && overlap <= 1.0, "overlap", overlap, "a value in (0, 1]");
  require(tail_dof > 0.0 && std::isfinite(tail_dof), "tail_dof", tail_dof, "a finite value > 0");
  require(anisotropy >= 1.0 && std::isfinite(anisotropy), "anisotropy", anisotropy,
          "a finite value >= 1");
  require(near_radius > 0.0 && std::isfinite(near_radius), "near_radius", near_radius,
          "a finite value > 0");
  require(cell > 0.0 && std::isfinite(cell), "cell", cell, "a finite value > 0");
  require(std::isfinite(score_separation), "score_separation", score_separation,
          "a finite value (< 0 = no scores)");
}

template <int Dim>
LabeledSet<Dim> make_synthetic(const SyntheticParams& requested) {
  requested.validate();
  SyntheticParams params = requested;
  if (params.negative) params.outlier_ratio = 1.0;
  find_generator(params.kind);  // throws UnknownName listing the kinds
  const auto it = std::find_if(kinds().begin(), kinds().end(),
                               [&](const Kind& k) { return k.info.name == params.kind; });
  Fill<Dim> fill = nullptr;
  if constexpr (Dim == 2) {
    fill = it->fill2;
  } else {
    fill = it->fill3;
  }
  if (fill == nullptr) {
    throw std::invalid_argument("generator '" + params.kind + "' does not exist in " +
                                std::to_string(Dim) + "D");
  }
  Draws<Dim> draw(params);
  const Rigid<Dim> T = draw.motion();
  LabeledSet<Dim> set;
  set.truth.labels = draw_labels(params, draw.rng);
  set.corr.source.resize(Dim, params.n);
  set.corr.target.resize(Dim, params.n);
  fill(params, draw, T, set);
  if (!params.negative) set.truth.T_target_source = T;
  set.truth.positive = !params.negative;
  if (params.score_separation >= 0.0) {
    std::mt19937_64 rng(derive_seed(params.seed, {0x53434f52u}));
    std::normal_distribution<double> g(0.0, 1.0);
    set.corr.score.resize(static_cast<std::size_t>(params.n));
    for (std::size_t i = 0; i < set.corr.score.size(); ++i) {
      set.corr.score[i] = params.score_separation * set.truth.labels[i] + g(rng);
    }
  }
  return set;
}

template <int Dim>
void add_pose_prior(LabeledSet<Dim>& set, double sigma_rot, double sigma_trans,
                    std::uint64_t seed) {
  require(sigma_rot > 0.0 && std::isfinite(sigma_rot), "prior sigma_rot", sigma_rot,
          "a finite value > 0");
  require(sigma_trans > 0.0 && std::isfinite(sigma_trans), "prior sigma_trans", sigma_trans,
          "a finite value > 0");
  if (!set.truth.T_target_source) {
    throw std::invalid_argument("a pose prior needs the set's true motion");
  }
  constexpr int kRot = Dim == 2 ? 1 : 3;
  std::mt19937_64 rng(derive_seed(seed, {0x5052u}));
  std::normal_distribution<double> g(0.0, 1.0);
  Eigen::Matrix<double, kRot, 1> w;
  Vec<Dim> v;
  for (int k = 0; k < kRot; ++k) w(k) = sigma_rot * g(rng);
  for (int d = 0; d < Dim; ++d) v(d) = sigma_trans * g(rng);
  // Odometry's guess T0 with T = Exp(delta) T0, i.e. T0 = Exp(delta)^-1 T.
  Rigid<Dim> E = Rigid<Dim>::Identity();
  if constexpr (Dim == 2) {
    E.linear() = Eigen::Rotation2Dd(w(0)).toRotationMatrix();
  } else {
    E.linear() = w.norm() > 0 ? Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix()
                              : Eigen::Matrix3d::Identity();
  }
  E.translation() = v;
  PosePrior<Dim> prior;
  prior.T_target_source = E.inverse() * *set.truth.T_target_source;
  prior.covariance.setZero();
  for (int k = 0; k < kRot; ++k) prior.covariance(k, k) = sigma_rot * sigma_rot;
  for (int d = 0; d < Dim; ++d) prior.covariance(kRot + d, kRot + d) = sigma_trans * sigma_trans;
  set.corr.prior = prior;
}

template LabeledSet<2> make_synthetic<2>(const SyntheticParams&);
template LabeledSet<3> make_synthetic<3>(const SyntheticParams&);
template void add_pose_prior<2>(LabeledSet<2>&, double, double, std::uint64_t);
template void add_pose_prior<3>(LabeledSet<3>&, double, double, std::uint64_t);

}  // namespace verifybench
