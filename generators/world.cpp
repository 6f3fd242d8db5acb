#include "generators/world.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "core/random.hpp"

namespace verifybench {

void Mesh::add_box(const Eigen::Vector3d& base, const Eigen::Vector3d& half, double yaw) {
  const int first = static_cast<int>(vertices.size());
  const double c = std::cos(yaw), s = std::sin(yaw);
  for (int k = 0; k < 8; ++k) {
    const double x = (k & 1 ? 1 : -1) * half.x(), y = (k & 2 ? 1 : -1) * half.y();
    const double z = (k & 4 ? 2.0 : 0.0) * half.z();
    vertices.emplace_back(static_cast<float>(base.x() + c * x - s * y),
                          static_cast<float>(base.y() + s * x + c * y),
                          static_cast<float>(base.z() + z));
  }
  // Corners: bit 0 = +x, bit 1 = +y, bit 2 = top. Two triangles a face, outward normals.
  static const int kFaces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                   {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : kFaces) {
    triangles.emplace_back(first + f[0], first + f[1], first + f[2]);
    triangles.emplace_back(first + f[0], first + f[2], first + f[3]);
  }
}

void Mesh::add_octahedron(const Eigen::Vector3d& centre, const Eigen::Vector3d& half) {
  const int first = static_cast<int>(vertices.size());
  const Eigen::Vector3d d[6] = {{half.x(), 0, 0},  {-half.x(), 0, 0}, {0, half.y(), 0},
                                {0, -half.y(), 0}, {0, 0, half.z()},  {0, 0, -half.z()}};
  for (const auto& v : d) vertices.push_back((centre + v).cast<float>());
  static const int kFaces[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                   {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (const auto& f : kFaces) triangles.emplace_back(first + f[0], first + f[1], first + f[2]);
}

void WorldParams::validate() const {
  auto positive = [](const char* name, double v) {
    if (!(v > 0.0) || !std::isfinite(v)) {
      throw std::invalid_argument(std::string("world: ") + name +
                                  " must be a positive number, got " + std::to_string(v));
    }
  };
  positive("road_half_width", road_half_width);
  positive("kerb_band", kerb_band);
  positive("cell", cell);
  positive("ground_cell", ground_cell);
  positive("sensor_height", sensor_height);
  if (!(building_setback >= road_half_width) || !(building_depth > building_setback) ||
      !std::isfinite(building_depth)) {
    throw std::invalid_argument(
        "world: need road_half_width <= building_setback < building_depth, got " +
        std::to_string(road_half_width) + ", " + std::to_string(building_setback) + ", " +
        std::to_string(building_depth));
  }
  if (!(margin >= 0.0) || !std::isfinite(margin)) {
    throw std::invalid_argument("world: margin must be >= 0, got " + std::to_string(margin));
  }
  for (double p : {kerb_density, building_density}) {
    if (!(p >= 0.0 && p <= 1.0)) {
      throw std::invalid_argument("world: densities must be in [0, 1], got " + std::to_string(p));
    }
  }
}

namespace {

// Path samples about every metre in a hash grid, for "nearest sample" queries.
class PathIndex {
 public:
  PathIndex(const std::vector<Rigid<3>>& path, double bucket) : bucket_(bucket) {
    for (std::size_t i = 0; i < path.size(); ++i) {
      const Eigen::Vector3d p = path[i].translation();
      if (!samples_.empty() && (p - samples_.back().position).norm() < 1.0 && i + 1 < path.size())
        continue;
      Eigen::Vector3d dir = path[i].linear().col(0);
      const std::size_t j = std::min(i + 1, path.size() - 1), h = i > 0 ? i - 1 : 0;
      if (j != h && (path[j].translation() - path[h].translation()).head<2>().norm() > 1e-6)
        dir = path[j].translation() - path[h].translation();
      dir.z() = 0.0;
      samples_.push_back({p, std::atan2(dir.y(), dir.x())});
      grid_[key(p.x(), p.y())].push_back(static_cast<int>(samples_.size()) - 1);
    }
  }
  struct Sample {
    Eigen::Vector3d position;
    double heading;
  };
  /// The nearest sample within `radius` (x-y distance), or -1.
  int nearest(double x, double y, double radius, double* distance) const {
    const long long r = static_cast<long long>(std::ceil(radius / bucket_));
    const long long cx = cell(x), cy = cell(y);
    int best = -1;
    double best_d = radius;
    for (long long dx = -r; dx <= r; ++dx) {
      for (long long dy = -r; dy <= r; ++dy) {
        const auto it = grid_.find(pack(cx + dx, cy + dy));
        if (it == grid_.end()) continue;
        for (int s : it->second) {
          const double d = (samples_[s].position.head<2>() - Eigen::Vector2d(x, y)).norm();
          if (d < best_d || (d == best_d && best >= 0 && s < best)) best_d = d, best = s;
        }
      }
    }
    *distance = best_d;
    return best;
  }
  const Sample& sample(int i) const { return samples_[i]; }
  const std::vector<Sample>& samples() const { return samples_; }

 private:
  long long cell(double v) const { return static_cast<long long>(std::floor(v / bucket_)); }
  static std::uint64_t pack(long long x, long long y) {  // unsigned: no shift of a negative
    return (static_cast<std::uint64_t>(x) << 32) ^ (static_cast<std::uint64_t>(y) & 0xffffffffULL);
  }
  std::uint64_t key(double x, double y) const { return pack(cell(x), cell(y)); }
  double bucket_;
  std::vector<Sample> samples_;
  std::unordered_map<std::uint64_t, std::vector<int>> grid_;
};

struct Placer {
  const WorldParams& p;
  const PathIndex& index;
  World& world;
  std::mt19937_64 rng;

  double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); }
  bool chance(double q) { return uniform(0.0, 1.0) < q; }

  void kerb_object(const Eigen::Vector3d& base, double heading) {
    const double kind = uniform(0.0, 1.0);
    Mesh& m = world.mesh;
    if (kind < 0.3) {  // pole, some with a lamp arm towards the road
      const double h = uniform(4.0, 8.0);
      m.add_box(base, {0.12, 0.12, h / 2}, heading);
      if (chance(0.5)) {
        m.add_box(base + Eigen::Vector3d(0, 0, h - 0.2), {0.9, 0.08, 0.08}, heading + M_PI / 2);
      }
      ++world.counts["poles"];
    } else if (kind < 0.6) {  // tree: trunk and crown
      const double h = uniform(2.0, 4.0), r = uniform(1.2, 3.0);
      m.add_box(base, {0.2, 0.2, h / 2}, uniform(0.0, M_PI));
      const int lobes = static_cast<int>(uniform(1.0, 4.0));  // a crown of 1-3 lobes
      for (int k = 0; k < lobes; ++k) {
        const Eigen::Vector3d off(uniform(-0.6, 0.6) * r, uniform(-0.6, 0.6) * r,
                                  uniform(0.5, 1.2) * r);
        const double rk = r * uniform(0.6, 1.0);
        m.add_octahedron(base + Eigen::Vector3d(0, 0, h) + off,
                         {rk, rk * uniform(0.7, 1.3), rk * uniform(0.8, 1.4)});
      }
      ++world.counts["trees"];
    } else if (kind < 0.85) {  // parked car: body and cabin, along the road
      const double yaw = heading + uniform(-0.1, 0.1) + (chance(0.5) ? M_PI : 0.0);
      m.add_box(base + Eigen::Vector3d(0, 0, 0.3), {2.1 + uniform(-0.3, 0.4), 0.9, 0.4}, yaw);
      m.add_box(base + Eigen::Vector3d(0, 0, 1.1), {1.1, 0.8, 0.3}, yaw);
      ++world.counts["cars"];
    } else {  // clutter: a bin, a bollard, a cabinet
      m.add_box(base, {uniform(0.2, 0.8), uniform(0.2, 0.8), uniform(0.3, 0.8)},
                uniform(0.0, M_PI));
      ++world.counts["clutter"];
    }
  }

  void building(const Eigen::Vector3d& base, double heading) {
    Mesh& m = world.mesh;
    const double hx = uniform(3.0, 9.0), hy = uniform(3.0, 9.0), h = uniform(4.0, 20.0);
    const double yaw = heading + uniform(-0.08, 0.08);
    m.add_box(base, {hx, hy, h / 2}, yaw);
    if (chance(0.4)) {  // a storey set back on top
      m.add_box(base + Eigen::Vector3d(0, 0, h), {hx * 0.6, hy * 0.6, uniform(1.5, 3.0)}, yaw);
    }
    // Facade detail on every side: balconies, sills, signs, bays, air conditioners, steps, each
    // placed at random, so that no two corners of the town look alike at a descriptor's radius.
    const double c = std::cos(yaw), s = std::sin(yaw);
    for (int side = 0; side < 4; ++side) {
      const bool along_x = side < 2;  // faces at +-hy (normal along the box's y) or at +-hx
      const double sign = side % 2 ? -1.0 : 1.0;
      const double face = along_x ? hy : hx, extent = along_x ? hx : hy;
      const int details = static_cast<int>(uniform(1.0, 6.0));
      for (int k = 0; k < details; ++k) {
        const double depth = uniform(0.2, 1.0), width = uniform(0.3, 2.0);
        const double u = uniform(-extent + width, extent - width);
        const double z = chance(0.3) ? 0.0 : uniform(0.5, h - 1.0);
        const double lx = along_x ? u : sign * (face + depth / 2);
        const double ly = along_x ? sign * (face + depth / 2) : u;
        const Eigen::Vector3d off(c * lx - s * ly, s * lx + c * ly, z);
        const Eigen::Vector3d half = along_x
                                         ? Eigen::Vector3d(width / 2, depth / 2, uniform(0.2, 1.2))
                                         : Eigen::Vector3d(depth / 2, width / 2, uniform(0.2, 1.2));
        m.add_box(base + off, half, yaw);
        ++world.counts["facade_details"];
      }
    }
    ++world.counts["buildings"];
  }
};

}  // namespace

World build_street_world(const std::vector<Rigid<3>>& path, const WorldParams& params) {
  params.validate();
  if (path.empty()) throw std::invalid_argument("world: empty path");
  const PathIndex index(path, 10.0);
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d hi = -lo;
  for (const auto& s : index.samples()) {
    lo = lo.cwiseMin(s.position.head<2>());
    hi = hi.cwiseMax(s.position.head<2>());
  }
  lo.array() -= params.margin;
  hi.array() += params.margin;
  const double cells_x = std::ceil((hi.x() - lo.x()) / params.ground_cell);
  const double cells_y = std::ceil((hi.y() - lo.y()) / params.ground_cell);
  if (!(cells_x <= 4096 && cells_y <= 4096)) {
    throw std::invalid_argument("world: ground grid of " + std::to_string(cells_x) + " x " +
                                std::to_string(cells_y) + " cells exceeds 4096 a side");
  }
  World world;
  Mesh& mesh = world.mesh;
  // Ground height: the nearest path sample's, sensor height below it; far vertices take the
  // height of the nearest sample found in a wider search, else the path's mean.
  double mean_z = 0.0;
  for (const auto& s : index.samples()) mean_z += s.position.z();
  mean_z /= static_cast<double>(index.samples().size());
  auto ground_z = [&](double x, double y) {
    double d = 0.0;
    int s = index.nearest(x, y, 40.0, &d);
    if (s < 0) s = index.nearest(x, y, 200.0, &d);
    return (s < 0 ? mean_z : index.sample(s).position.z()) - params.sensor_height;
  };
  const int nx = static_cast<int>(cells_x), ny = static_cast<int>(cells_y);
  const int first = static_cast<int>(mesh.vertices.size());
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      const double x = lo.x() + i * params.ground_cell, y = lo.y() + j * params.ground_cell;
      mesh.vertices.emplace_back(static_cast<float>(x), static_cast<float>(y),
                                 static_cast<float>(ground_z(x, y)));
    }
  }
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const int a = first + j * (nx + 1) + i, b = a + 1, c = a + nx + 1, d = c + 1;
      mesh.triangles.emplace_back(a, b, d);
      mesh.triangles.emplace_back(a, d, c);
    }
  }
  // Objects, one draw per placement cell.
  const long long gx0 = static_cast<long long>(std::floor(lo.x() / params.cell));
  const long long gy0 = static_cast<long long>(std::floor(lo.y() / params.cell));
  const long long gx1 = static_cast<long long>(std::ceil(hi.x() / params.cell));
  const long long gy1 = static_cast<long long>(std::ceil(hi.y() / params.cell));
  for (long long gy = gy0; gy < gy1; ++gy) {
    for (long long gx = gx0; gx < gx1; ++gx) {
      Placer placer{params, index, world,
                    std::mt19937_64(derive_seed(params.seed, {static_cast<std::uint64_t>(gx),
                                                              static_cast<std::uint64_t>(gy)}))};
      const double x = (static_cast<double>(gx) + placer.uniform(0.0, 1.0)) * params.cell;
      const double y = (static_cast<double>(gy) + placer.uniform(0.0, 1.0)) * params.cell;
      double d = 0.0;
      const int s = index.nearest(x, y, params.building_depth, &d);
      if (s < 0 || d < params.road_half_width) continue;
      const double heading = index.sample(s).heading;
      const Eigen::Vector3d base(x, y, index.sample(s).position.z() - params.sensor_height);
      if (d < params.road_half_width + params.kerb_band) {
        if (placer.chance(params.kerb_density)) placer.kerb_object(base, heading);
      } else if (d >= params.building_setback + 3.0 && placer.chance(params.building_density)) {
        // The footprint (half sides up to 9 m) must keep clear of every part of the road.
        const std::size_t before = mesh.vertices.size();
        const std::size_t before_tri = mesh.triangles.size();
        const auto counts = world.counts;
        placer.building(base, heading);
        bool clear = true;
        for (std::size_t v = before; v < mesh.vertices.size() && clear; ++v) {
          double dv = 0.0;
          const Eigen::Vector3f& p = mesh.vertices[v];
          clear = index.nearest(p.x(), p.y(), params.building_setback, &dv) < 0;
        }
        if (!clear) {  // drawn too close to the road: taken back
          mesh.vertices.resize(before);
          mesh.triangles.resize(before_tri);
          world.counts = counts;
        }
      }
    }
  }
  world.counts["triangles"] = static_cast<int>(mesh.triangles.size());
  return world;
}

std::vector<Rigid<3>> block_laps(double width, double height, int laps, double step) {
  if (!(width > 0) || !(height > 0) || !(step > 0) || laps < 0 ||
      2 * (width + height) / step * laps > 1e7) {
    throw std::invalid_argument("block_laps: width " + std::to_string(width) + ", height " +
                                std::to_string(height) + ", laps " + std::to_string(laps) +
                                ", step " + std::to_string(step) +
                                ": sizes and step must be > 0, laps >= 0, at most 1e7 poses");
  }
  const double W = width, H = height;
  std::vector<Rigid<3>> path;
  for (int lap = 0; lap < laps; ++lap) {
    for (double s = 0; s < 2 * (W + H); s += step) {
      double x, y, yaw;
      if (s < W)
        x = s, y = 0, yaw = 0;
      else if (s < W + H)
        x = W, y = s - W, yaw = M_PI / 2;
      else if (s < 2 * W + H)
        x = W - (s - W - H), y = H, yaw = M_PI;
      else
        x = 0, y = H - (s - 2 * W - H), yaw = -M_PI / 2;
      Rigid<3> T = Rigid<3>::Identity();
      T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      T.translation() << x, y, 0.0;
      path.push_back(T);
    }
  }
  return path;
}

const std::vector<ParamRow<WorldParams>>& world_param_rows() {
  using P = WorldParams;
  static const std::vector<ParamRow<P>> rows = {
      field_row(&P::building_density, "world-building-density", "building_density", "P",
                "chance of a building in a block cell", 0.0, 1.0, "a value in [0, 1]"),
      field_row(&P::kerb_density, "world-kerb-density", "kerb_density", "P",
                "chance of a pole, tree, car or clutter in a kerb cell", 0.0, 1.0,
                "a value in [0, 1]")};
  return rows;
}

}  // namespace verifybench
