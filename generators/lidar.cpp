#include "generators/lidar.hpp"

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

#ifdef VERIFYBENCH_HAVE_EMBREE
#include <embree3/rtcore.h>
#endif

namespace verifybench {

void LidarParams::validate() const {
  auto fail = [](const std::string& field, double v, const std::string& want) {
    throw std::invalid_argument("lidar: " + field + " must be " + want + ", got " +
                                std::to_string(v));
  };
  if (beams < 1 || beams > 1024) fail("beams", beams, "in [1, 1024]");
  if (columns < 1 || columns > 100000) fail("columns", columns, "in [1, 100000]");
  if (!(fov_up_deg > fov_down_deg) || !(fov_up_deg <= 90.0) || !(fov_down_deg >= -90.0))
    fail("fov_up_deg", fov_up_deg, "above fov_down_deg, both within [-90, 90]");
  if (!(min_range >= 0.0) || !(max_range > min_range) || !std::isfinite(max_range))
    fail("max_range", max_range, "finite and above min_range >= 0");
  if (!(range_noise >= 0.0) || !std::isfinite(range_noise)) fail("range_noise", range_noise, ">= 0");
  if (!(dropout >= 0.0 && dropout < 1.0)) fail("dropout", dropout, "in [0, 1)");
}

#ifdef VERIFYBENCH_HAVE_EMBREE

bool lidar_available() { return true; }

struct LidarSimulator::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

LidarSimulator::LidarSimulator(const Mesh& mesh) : impl_(std::make_unique<Impl>()) {
  // One Embree thread: scans are cast in parallel by the caller's pool, and results never
  // depend on threads (every ray is independent).
  impl_->device = rtcNewDevice("threads=1");
  if (!impl_->device) throw std::runtime_error("embree: cannot create a device");
  impl_->scene = rtcNewScene(impl_->device);
  if (!mesh.triangles.empty()) {
    RTCGeometry geom = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0,
                                                          RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                          mesh.vertices.size()));
    auto* t = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0,
                                                             RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
                                                             mesh.triangles.size()));
    if (!v || !t) {
      rtcReleaseGeometry(geom);
      throw std::runtime_error("embree: cannot allocate the mesh buffers");
    }
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
      for (int k = 0; k < 3; ++k) v[3 * i + k] = mesh.vertices[i](k);
    }
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
      for (int k = 0; k < 3; ++k) {
        const int idx = mesh.triangles[i](k);
        if (idx < 0 || static_cast<std::size_t>(idx) >= mesh.vertices.size()) {
          rtcReleaseGeometry(geom);
          throw std::invalid_argument("mesh: triangle " + std::to_string(i) + " names vertex " +
                                      std::to_string(idx) + " of " +
                                      std::to_string(mesh.vertices.size()));
        }
        t[3 * i + k] = static_cast<unsigned>(idx);
      }
    }
    rtcCommitGeometry(geom);
    rtcAttachGeometry(impl_->scene, geom);
    rtcReleaseGeometry(geom);
  }
  rtcCommitScene(impl_->scene);
  if (rtcGetDeviceError(impl_->device) != RTC_ERROR_NONE) {
    throw std::runtime_error("embree: building the scene failed");
  }
}

LidarSimulator::~LidarSimulator() = default;

double LidarSimulator::cast(const Eigen::Vector3d& o, const Eigen::Vector3d& d) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh{};
  rh.ray.org_x = static_cast<float>(o.x());
  rh.ray.org_y = static_cast<float>(o.y());
  rh.ray.org_z = static_cast<float>(o.z());
  const Eigen::Vector3d u = d.normalized();
  rh.ray.dir_x = static_cast<float>(u.x());
  rh.ray.dir_y = static_cast<float>(u.y());
  rh.ray.dir_z = static_cast<float>(u.z());
  rh.ray.tnear = 0.0f;
  rh.ray.tfar = std::numeric_limits<float>::infinity();
  rh.ray.mask = static_cast<unsigned>(-1);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::numeric_limits<double>::infinity();
  return rh.ray.tfar;
}

std::vector<Eigen::Vector3f> LidarSimulator::scan(const Rigid<3>& T, const LidarParams& p,
                                                  std::uint64_t seed) const {
  p.validate();
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, p.range_noise);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Eigen::Vector3f> points;
  points.reserve(static_cast<std::size_t>(p.beams) * p.columns);
  const Eigen::Vector3d origin = T.translation();
  const double deg = M_PI / 180.0;
  for (int c = 0; c < p.columns; ++c) {
    const double az = 2.0 * M_PI * c / p.columns;
    for (int b = 0; b < p.beams; ++b) {
      const double el =
          (p.beams == 1 ? p.fov_down_deg
                        : p.fov_down_deg + (p.fov_up_deg - p.fov_down_deg) * b / (p.beams - 1)) *
          deg;
      const Eigen::Vector3d dir_s(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az),
                                  std::sin(el));
      const double r = cast(origin, T.linear() * dir_s);
      // Noise and dropout are drawn for every ray, hit or not, so one ray's draw never shifts
      // another's when the scene changes.
      const double dr = p.range_noise > 0.0 ? noise(rng) : 0.0;
      const bool lost = unit(rng) < p.dropout;
      if (!std::isfinite(r) || r < p.min_range || r > p.max_range || lost) continue;
      points.push_back(((r + dr) * dir_s).cast<float>());
    }
  }
  return points;
}

#else

bool lidar_available() { return false; }
struct LidarSimulator::Impl {};
LidarSimulator::LidarSimulator(const Mesh&) {
  throw std::runtime_error("this verifybench was built without Embree (VERIFYBENCH_WITH_EMBREE)");
}
LidarSimulator::~LidarSimulator() = default;
double LidarSimulator::cast(const Eigen::Vector3d&, const Eigen::Vector3d&) const {
  return std::numeric_limits<double>::infinity();
}
std::vector<Eigen::Vector3f> LidarSimulator::scan(const Rigid<3>&, const LidarParams&,
                                                  std::uint64_t) const {
  return {};
}

#endif

const std::vector<ParamRow<LidarParams>>& lidar_param_rows() {
  using P = LidarParams;
  static const std::vector<ParamRow<P>> rows = {
      field_row(&P::beams, "lidar-beams", "beams", "K", "beams, evenly from +2 to -24.8 deg", 1,
                1024, "an integer in [1, 1024]"),
      field_row(&P::columns, "lidar-columns", "columns", "K", "azimuth steps a sweep", 1, 100000,
                "an integer in [1, 100000]"),
      field_row(&P::max_range, "lidar-max-range", "max_range_m", "M", "farthest return [m]", 3.0,
                1e4, "a value in [3, 10000]"),
      field_row(&P::range_noise, "lidar-noise", "range_noise_m", "M", "range noise sigma [m]", 0.0,
                10.0, "a value in [0, 10]"),
      field_row(&P::dropout, "lidar-dropout", "dropout", "P", "probability of a lost return", 0.0,
                0.99, "a value in [0, 0.99]")};
  return rows;
}

}  // namespace verifybench
