#pragma once
// Synthetic correspondence sets with a drawn rigid motion and per-correspondence labels, in
// several kinds (`list_generators()`): uniform outliers, and the structured outliers real
// front ends produce.
#include <cstdint>
#include <string>
#include <vector>

#include "core/correspondences.hpp"
#include "core/param_rows.hpp"

namespace verifybench {

struct SyntheticParams {
  int n = 500;                   ///< correspondences, >= 1
  double outlier_ratio = 0.5;    ///< fraction of outliers in [0, 1]; round(n * ratio) outliers
  double noise = 0.01;           ///< Gaussian sigma per axis added to inlier targets [m], >= 0
  double extent = 10.0;          ///< source points uniform in a cube (square) of this side [m], > 0
  double max_translation = 5.0;  ///< each translation component uniform in [-max, max] [m], >= 0
  std::uint64_t seed = 1;        ///< every draw comes from this seed
  std::string kind = "uniform";  ///< one of list_generators()
  /// 3D: the true rotation is a yaw about z, uniform, roll and pitch 0 (a ground vehicle's loop;
  /// the regime of Quatro's quasi-SO(3)); false: uniform on SO(3). No effect in 2D.
  bool planar_motion = false;
  // Per-kind shape (ignored by the other kinds):
  double group_ratio = 0.5;   ///< rigid-group: wrong group size / inlier count, > 0
  double grid_spacing = 2.0;  ///< repetitive: lattice step along and across the corridor [m]
  double overlap = 0.3;       ///< partial-overlap: fraction of the cube holding the inliers
  double tail_dof = 3.0;      ///< heavy-tailed: Student-t degrees of freedom, > 0
  double anisotropy = 5.0;    ///< anisotropic: sigma along the sensor ray / across it, >= 1
  double near_radius = 1.0;   ///< near-true and bev-orb: outliers lie this far from the truth [m]
  double cell = 0.5;          ///< bev-orb: bird's-eye-view cell size [m]
  /// Match scores as a descriptor matcher would give them: score = separation * label + N(0, 1),
  /// so inliers tend to score higher (PROSAC's input); < 0 = no scores. Drawn from their own
  /// stream, so the points do not depend on it.
  double score_separation = 1.0;
  /// A negative pair (issue #13): two sides that share no motion. Every correspondence is an
  /// outlier of the kind (outlier_ratio is taken as 1: unrelated points for uniform, the
  /// repetitive corridor's shifted pillars, near-true's displaced points, ...), the set has no
  /// true motion and is expected to be rejected.
  bool negative = false;
  void validate() const;  ///< throws std::invalid_argument naming the field and value
};

/// The per-kind shape settings as rows (core/param_rows.hpp), declared once in synthetic_rows.cpp:
/// `sweep`'s options (--planar-motion, --group-ratio, ... --score-separation), its report's
/// generator_shape block and Python's synthetic() keywords.
const std::vector<ParamRow<SyntheticParams>>& synthetic_shape_rows();

struct GeneratorInfo {
  std::string name;
  std::string description;  ///< one line, shown by `verifybench list`
  bool supports_2d = true, supports_3d = true;
};

/// The generator kinds, in a stable order.
std::vector<GeneratorInfo> list_generators();
/// Throws UnknownName ("unknown kind 'x' (known: uniform, ...)").
const GeneratorInfo& find_generator(const std::string& kind);

/// Draws a set of `params.kind`. Common to every kind: the rotation is uniform on SO(Dim), each
/// translation component uniform in [-max_translation, max_translation], round(n * ratio)
/// outliers interleaved with the inliers in a random order, labels 1 for the true inliers;
/// truth.positive = !negative.
/// Throws std::invalid_argument for an unknown kind (listing the known ones), a kind that does not
/// exist in this dimension, or a bad parameter.
template <int Dim>
LabeledSet<Dim> make_synthetic(const SyntheticParams& params);

/// Adds a pose prior as odometry would give it: the true motion perturbed on the left by a draw
/// delta ~ N(0, diag(sigma_rot^2 (per rotation axis), sigma_trans^2 (per axis))), with that
/// covariance. sigma_rot in radians. Seeded from `seed`.
template <int Dim>
void add_pose_prior(LabeledSet<Dim>& set, double sigma_rot, double sigma_trans, std::uint64_t seed);

}  // namespace verifybench
