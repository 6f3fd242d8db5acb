#include "core/transform.hpp"

#include <Eigen/SVD>
#include <sstream>

#include "core/errors.hpp"

namespace verifybench {

template <int Dim>
PublishedRigid<Dim> published_rigid(const Eigen::Matrix<double, Dim + 1, Dim + 1>& M,
                                    const std::string& where) {
  using Mat = Eigen::Matrix<double, Dim, Dim>;
  if (!M.allFinite()) throw InputError(where + ": the matrix has a non-finite entry");
  Eigen::Matrix<double, 1, Dim + 1> last = Eigen::Matrix<double, 1, Dim + 1>::Zero();
  last(Dim) = 1.0;
  if ((M.row(Dim) - last).norm() > 1e-6) throw InputError(where + ": last row must be 0 ... 0 1");
  const Mat R = M.template topLeftCorner<Dim, Dim>();
  PublishedRigid<Dim> out;
  out.rotation_residual = (R.transpose() * R - Mat::Identity()).norm();
  const double det = R.determinant();
  if (!(out.rotation_residual <= kRotationTolerance) || !(det > 0.0)) {
    std::ostringstream msg;
    msg << where << ": rotation block is not a rotation (|R^T R - I| = " << out.rotation_residual
        << ", limit " << kRotationTolerance << "; det = " << det << ")";
    throw InputError(msg.str());
  }
  // The nearest rotation: U V^T of R's SVD, the last column of U flipped if that is a reflection.
  Eigen::JacobiSVD<Mat> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Mat U = svd.matrixU();
  if ((U * svd.matrixV().transpose()).determinant() < 0.0) U.col(Dim - 1) *= -1.0;
  out.T.linear() = U * svd.matrixV().transpose();
  out.T.translation() = M.template topRightCorner<Dim, 1>();
  return out;
}

template PublishedRigid<2> published_rigid<2>(const Eigen::Matrix3d&, const std::string&);
template PublishedRigid<3> published_rigid<3>(const Eigen::Matrix4d&, const std::string&);

}  // namespace verifybench
