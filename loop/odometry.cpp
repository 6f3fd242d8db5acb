// The odometry kinds by name (loop/odometry.hpp), the built-in ones added on first use.
#include "loop/odometry.hpp"

#include "core/registry.hpp"

namespace verifybench {
namespace {

Registry<OdometryInfo>& odometries() {
  static Registry<OdometryInfo> reg("odometry", Registry<OdometryInfo>::Order::as_added);
  static const bool builtins = [] {
    reg.add(drift_odometry_kind());
    reg.add(gicp_odometry_kind());
    reg.add(poses_odometry_kind("poses", "--odometry-file's poses (e.g. KISS-ICP's output)"));
    reg.add(poses_odometry_kind("log", "the recording's own odometry (a CARMEN log's)"));
    return true;
  }();
  (void)builtins;
  return reg;
}

}  // namespace

std::vector<OdometryInfo> list_odometries() { return odometries().list(); }

const OdometryInfo& find_odometry(const std::string& name) { return odometries().get(name); }

void register_odometry(OdometryInfo info) { odometries().add(std::move(info)); }

}  // namespace verifybench
