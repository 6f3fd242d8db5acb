#include "generators/synthetic.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <sstream>
#include <stdexcept>

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

}  // namespace

void SyntheticParams::validate() const {
  require(n >= 1, "n", n, "an integer >= 1");
  require(outlier_ratio >= 0.0 && outlier_ratio <= 1.0, "outlier_ratio", outlier_ratio,
          "a value in [0, 1]");
  require(noise >= 0.0 && std::isfinite(noise), "noise", noise, "a finite value >= 0");
  require(extent > 0.0 && std::isfinite(extent), "extent", extent, "a finite value > 0");
  require(max_translation >= 0.0 && std::isfinite(max_translation), "max_translation",
          max_translation, "a finite value >= 0");
}

template <int Dim>
LabeledSet<Dim> make_synthetic(const SyntheticParams& params) {
  params.validate();
  using Vec = Eigen::Matrix<double, Dim, 1>;
  std::mt19937_64 rng(params.seed);
  std::uniform_real_distribution<double> unit(-0.5, 0.5);
  std::uniform_real_distribution<double> shift(-params.max_translation, params.max_translation);
  std::normal_distribution<double> noise(0.0, 1.0);

  Rigid<Dim> T = Rigid<Dim>::Identity();
  T.linear() = random_rotation<Dim>(rng);
  for (int d = 0; d < Dim; ++d) T.translation()(d) = shift(rng);

  const int n = params.n;
  const int outliers = static_cast<int>(std::lround(params.outlier_ratio * n));
  std::vector<std::uint8_t> labels(static_cast<std::size_t>(n), 0);
  std::fill(labels.begin(), labels.begin() + (n - outliers), 1);
  std::shuffle(labels.begin(), labels.end(), rng);

  auto draw_in_cube = [&] {
    Vec p;
    for (int d = 0; d < Dim; ++d) p(d) = params.extent * unit(rng);
    return p;
  };
  LabeledSet<Dim> set;
  set.corr.source.resize(Dim, n);
  set.corr.target.resize(Dim, n);
  for (int i = 0; i < n; ++i) {
    const Vec m = draw_in_cube();
    Vec q;
    if (labels[static_cast<std::size_t>(i)]) {
      q = T * m;
      for (int d = 0; d < Dim; ++d) q(d) += params.noise * noise(rng);
    } else {
      q = T * draw_in_cube();  // an unrelated point of the same scene
    }
    set.corr.source.col(i) = m;
    set.corr.target.col(i) = q;
  }
  set.truth.T_target_source = T;
  set.truth.labels = std::move(labels);
  return set;
}

template LabeledSet<2> make_synthetic<2>(const SyntheticParams&);
template LabeledSet<3> make_synthetic<3>(const SyntheticParams&);

}  // namespace verifybench
