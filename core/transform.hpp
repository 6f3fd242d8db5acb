#pragma once
// Ground-truth motions as datasets publish them: one rule for every reader (text dumps, dump v1,
// T files). Printed digits leave the rotation block slightly off SO(Dim) (3DMatch's GTmat.txt
// files reach |R^T R - I| = 1e-4), so up to kRotationTolerance it is projected onto SO(Dim) and
// the residual recorded; beyond, the matrix is refused naming the file, the value and the limit.
#include <Eigen/Core>
#include <string>

#include "core/correspondences.hpp"

namespace verifybench {

inline constexpr double kRotationTolerance = 1e-2;  ///< largest accepted |R^T R - I|_F

template <int Dim>
struct PublishedRigid {
  Rigid<Dim> T = Rigid<Dim>::Identity();  ///< rotation projected onto SO(Dim)
  double rotation_residual = 0.0;         ///< |R^T R - I|_F of the matrix as published
};

/// Checks and projects a homogeneous (Dim+1)x(Dim+1) matrix; `where` ("FILE", "FILE: field X")
/// starts the InputError message. Refuses non-finite entries, a last row other than 0 ... 0 1
/// (within 1e-6), det R <= 0, and |R^T R - I|_F > kRotationTolerance.
template <int Dim>
PublishedRigid<Dim> published_rigid(const Eigen::Matrix<double, Dim + 1, Dim + 1>& M,
                                    const std::string& where);

/// A planar motion as an SE(3) motion (rotation about z, translation in x-y); a 3D one as it is.
inline Rigid<3> lift_planar(const Rigid<2>& T) {
  Rigid<3> out = Rigid<3>::Identity();
  out.linear().topLeftCorner<2, 2>() = T.linear();
  out.translation().head<2>() = T.translation();
  return out;
}
inline Rigid<3> lift_planar(const Rigid<3>& T) { return T; }

}  // namespace verifybench
