#pragma once
// The RANSACs users already have, registered as solvers: pcl-* (PCL 1.13) and open3d-* (Open3D
// 0.16), each only when the build has that library (VERIFYBENCH_WITH_PCL / _OPEN3D).
namespace verifybench {

/// Registers the peers this build has, once.
void register_peer_solvers();

}  // namespace verifybench
