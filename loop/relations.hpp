#pragma once
// Kuemmerle et al.'s relation error ("On measuring the accuracy of SLAM algorithms", Autonomous
// Robots 27(4), 2009, Eq. 1-2): a set of reference relations delta*_ij, each the relative motion
// between the poses at two timestamps, against the estimate's delta_ij = x_i^-1 x_j; the error of
// one relation is delta*_ij^-1 delta_ij, reported as its mean translation [m] and mean rotation
// [deg] over the relations (the paper's "absolute" errors), each with its mean square.
// The estimate is known at the run's frames only; the pose at another timestamp t is the nearest
// frame's estimate carried to t by the recording's own odometry (x(t) = x_k o_k^-1 o(t), o
// interpolated between logged odometry samples), so a relation inside one stretch between frames
// costs what the odometry costs, and relations across a loop see what the loops changed.
#include <limits>
#include <string>
#include <vector>

#include "core/correspondences.hpp"

namespace verifybench {

struct Relation {
  double t1 = 0, t2 = 0;  ///< [s] the two poses' timestamps
  Rigid<3> T;             ///< delta*: the pose at t2 in the frame of the pose at t1
};

/// A relations file as Kuemmerle et al. publish them: `t1 t2 x y z roll pitch yaw` per line
/// (metres, radians; roll about x, pitch about y, yaw about z, R = Rz(yaw) Ry(pitch) Rx(roll)),
/// '#' comments and blank lines skipped. Throws InputError naming the file, the line, the field
/// and the value (a missing or extra field, a non-number, a non-finite value, t2 < t1) or a file
/// without relations.
std::vector<Relation> read_relations(const std::string& path);

struct RelationError {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  int relations = 0;  ///< in the file
  int used = 0;       ///< with both timestamps inside the logged odometry's span
  double translation_m = kNaN, translation_sq = kNaN;  ///< mean |t| [m], mean |t|^2 [m^2]
  double rotation_deg = kNaN, rotation_sq = kNaN;      ///< mean angle [deg], mean angle^2 [deg^2]
};

/// The relation error of the estimate `frame_poses` at `frame_stamps` (ascending), carried between
/// frames by the odometry `odometry` at `odometry_stamps` (ascending; the recording's whole
/// stream). Throws std::invalid_argument for mismatched lengths, no frame or fewer than 2
/// odometry samples.
RelationError relation_error(const std::vector<Relation>& relations,
                             const std::vector<double>& frame_stamps,
                             const std::vector<Rigid<3>>& frame_poses,
                             const std::vector<double>& odometry_stamps,
                             const std::vector<Rigid<3>>& odometry);

}  // namespace verifybench
