// CARMEN logs (.clf/.log, one message a line), as CARMEN's logger reads them back (readlog.c:
// carmen_string_to_robot_laser_message_orig, carmen_laser_guess_angle_increment) and the Radish /
// Freiburg SLAM evaluation data sets publish them (../shared/data/README.md, radish2d):
//   FLASER n r1 .. rn x y theta odom_x odom_y odom_theta ipc_timestamp ipc_hostname
//   logger_timestamp
//     ranges [m] from -90 deg, 1 deg apart for 180 or 181 readings, 0.5 for 360/361, 0.25 for
//     400/401, else 180 deg / (n - 1); readings of kMaxRange or more are no return
//   ROBOTLASER1 laser_type start_angle fov angular_resolution maximum_range accuracy
//     remission_mode n r1 .. rn m e1 .. em laser_x laser_y laser_theta robot_x robot_y robot_theta
//     tv rv forward_safety_dist side_safety_dist turn_axis ipc_timestamp ipc_hostname
//     logger_timestamp
// Scans are FLASER lines, or ROBOTLASER1 lines in a log with no FLASER. Points lie in the laser's
// plane (z = 0); `odometry` is the laser's logged pose (x y theta), a yaw about z; stamps are
// ipc_timestamp, scans sorted by it (intel.clf logs some a few ms out of order).
// With SourceOptions::reference, a corrected log (FLASER lines whose poses are the reference, its
// timestamps the raw logger_timestamp printed to fewer digits): a corrected scan meets the raw scan
// whose logger_timestamp rounds to its printed digits (%g, 6 significant digits at least); where
// several do (intel after 1000 s logs bursts 1 ms apart), the one with the same ranges. Corrected
// logs are subsampled, so only the scans they correct are kept (the note says how many).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <string_view>

#include "core/errors.hpp"
#include "loop/sources/common.hpp"

namespace verifybench::sources {
namespace {
namespace fs = std::filesystem;

constexpr double kMaxRange = 80.0;  // [m] CARMEN's FLASER maximum_range; SICK LMS reads 81.83

struct Scan {
  std::vector<float> ranges;
  double start = 0, step = 0, max_range = kMaxRange;  // [rad], [rad], [m]
  double x = 0, y = 0, theta = 0;                     // laser pose
  double stamp = 0, logger = 0;                       // ipc_timestamp, logger_timestamp [s]
  std::string logger_token;                           // as printed
  long long line = 0;
};

std::vector<std::string_view> tokens_of(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    const std::size_t b = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > b) out.push_back(line.substr(b, i - b));
  }
  return out;
}

// Reads the fields of one message line in order, naming the field of a bad value.
class Fields {
 public:
  Fields(const std::vector<std::string_view>& t, const std::string& path, long long line)
      : t_(t), path_(path), line_(line) {}
  /// `index` > 0 numbers a repeated field ("range 3"); names are built only for a message.
  double real(const char* name, int index = 0) {
    const std::string_view tok = next(name, index);
    const ParsedReal v = parse_real_token(tok);
    if (v.error != NumberError::none) fail(name, index, tok, "is not a finite number");
    return v.value;
  }
  int count(const char* name) {
    const std::string_view tok = next(name);
    const auto v = parse_unsigned_token(tok);
    if (!v || *v > 100000) fail(name, 0, tok, "is not a reading count");
    return static_cast<int>(*v);
  }
  std::string_view next(const char* name, int index = 0) {
    if (i_ >= t_.size()) {
      input_error(path_, line_,
                  std::string(t_[0]) + " ends before field " + std::to_string(i_ + 1) + " (" +
                      label(name, index) + ")");
    }
    return t_[i_++];
  }
  std::size_t left() const { return t_.size() - i_; }

 private:
  static std::string label(const char* name, int index) {
    return index > 0 ? name + (" " + std::to_string(index)) : std::string(name);
  }
  [[noreturn]] void fail(const char* name, int index, std::string_view tok, const char* what) {
    input_error(path_, line_,
                "field " + std::to_string(i_) + " (" + label(name, index) + ") '" +
                    std::string(tok) + "' " + what);
  }
  const std::vector<std::string_view>& t_;
  const std::string& path_;
  long long line_;
  std::size_t i_ = 1;  // after the message name
};

double flaser_step(int n) {
  if (n == 180 || n == 181) return M_PI / 180.0;
  if (n == 360 || n == 361) return M_PI / 360.0;
  if (n == 400 || n == 401) return M_PI / 720.0;
  return n > 1 ? M_PI / (n - 1) : 0.0;
}

void read_ranges(Fields& f, Scan& s, int n) {
  s.ranges.resize(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    s.ranges[static_cast<std::size_t>(k)] = static_cast<float>(f.real("range", k + 1));
  }
}

Scan parse_flaser(Fields& f) {
  Scan s;
  const int n = f.count("num_readings");
  read_ranges(f, s, n);
  s.start = -M_PI / 2;
  s.step = flaser_step(n);
  s.x = f.real("x");
  s.y = f.real("y");
  s.theta = f.real("theta");
  f.real("odom_x");
  f.real("odom_y");
  f.real("odom_theta");
  return s;
}

Scan parse_robotlaser(Fields& f) {
  Scan s;
  f.real("laser_type");
  s.start = f.real("start_angle");
  f.real("field_of_view");
  s.step = f.real("angular_resolution");
  s.max_range = f.real("maximum_range");
  f.real("accuracy");
  f.real("remission_mode");
  read_ranges(f, s, f.count("num_readings"));
  const int m = f.count("num_remissions");
  for (int k = 0; k < m; ++k) f.real("remission", k + 1);
  s.x = f.real("laser_pose_x");
  s.y = f.real("laser_pose_y");
  s.theta = f.real("laser_pose_theta");
  for (const char* name : {"robot_pose_x", "robot_pose_y", "robot_pose_theta", "tv", "rv",
                           "forward_safety_dist", "side_safety_dist", "turn_axis"}) {
    f.real(name);
  }
  return s;
}

// Every laser scan of the log, in file order: FLASER lines, else ROBOTLASER1 lines.
std::vector<Scan> read_log(const std::string& path) {
  std::ifstream in(path);
  if (!in) input_error(path, 0, "cannot open");
  std::vector<Scan> flaser, robotlaser;
  long long line_no = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    const bool fl = line.rfind("FLASER ", 0) == 0, rl = line.rfind("ROBOTLASER1 ", 0) == 0;
    if (!fl && !rl) continue;
    const auto t = tokens_of(line);
    Fields f(t, path, line_no);
    Scan s = fl ? parse_flaser(f) : parse_robotlaser(f);
    s.stamp = f.real("ipc_timestamp");
    f.next("ipc_hostname");
    s.logger_token = std::string(f.next("logger_timestamp"));
    const ParsedReal logger = parse_real_token(s.logger_token);
    if (logger.error != NumberError::none) {
      input_error(path, line_no, "logger_timestamp '" + s.logger_token + "' is not a number");
    }
    s.logger = logger.value;
    if (f.left() != 0) {
      input_error(
          path, line_no,
          std::to_string(f.left()) +
              " field(s) after logger_timestamp: the reading count does not match the line");
    }
    s.line = line_no;
    (fl ? flaser : robotlaser).push_back(std::move(s));
  }
  return flaser.empty() ? robotlaser : flaser;
}

// Half a unit of the last digit `token` holds, as %g prints it: 6 significant digits at least
// (trailing zeros dropped), more when printed.
double printed_half_unit(const std::string& token, double value) {
  const auto e = token.find_first_of("eE");
  const std::string mantissa = token.substr(0, e);
  const auto dot = mantissa.find('.');
  int last = dot == std::string::npos ? 0 : -static_cast<int>(mantissa.size() - dot - 1);
  if (e != std::string::npos) last += std::stoi(token.substr(e + 1));
  const int magnitude = value == 0 ? 0 : static_cast<int>(std::floor(std::log10(std::abs(value))));
  return 0.5 * std::pow(10.0, std::min(last, magnitude - 5)) * (1 + 1e-9);
}

bool same_ranges(const Scan& a, const Scan& b) {
  if (a.ranges.size() != b.ranges.size()) return false;
  for (std::size_t k = 0; k < a.ranges.size(); ++k) {
    if (std::abs(a.ranges[k] - b.ranges[k]) > 0.005f) return false;
  }
  return true;
}

Rigid<3> planar(double x, double y, double theta) {
  Rigid<3> T = Rigid<3>::Identity();
  T.linear() = Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() << x, y, 0;
  return T;
}

class CarmenLog : public SequenceSource {
 public:
  CarmenLog(SequenceInfo info, std::vector<Scan> scans)
      : info_(std::move(info)), scans_(std::move(scans)) {}
  const SequenceInfo& info() const override { return info_; }
  Cloud points(int i) const override {
    if (i < 0 || i >= size()) {
      throw std::out_of_range("scan " + std::to_string(i) + " of " + std::to_string(size()) +
                              " in " + info_.dir);
    }
    const Scan& s = scans_[static_cast<std::size_t>(i)];
    Cloud cloud;
    for (std::size_t k = 0; k < s.ranges.size(); ++k) {
      const double r = s.ranges[k];
      if (!(r > 0) || r >= s.max_range) continue;  // no return
      const double a = s.start + static_cast<double>(k) * s.step;
      cloud.emplace_back(static_cast<float>(r * std::cos(a)), static_cast<float>(r * std::sin(a)),
                         0.0f);
    }
    return cloud;
  }

 private:
  SequenceInfo info_;
  std::vector<Scan> scans_;
};

// The log file itself, or the only .clf/.log of a folder; "" when neither.
std::string find_log(const std::string& dir) {
  if (is_file(dir)) return dir;
  if (!is_dir(dir)) return "";
  std::vector<std::string> logs;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string ext = e.path().extension().string();
    if (e.is_regular_file(ec) && (ext == ".clf" || ext == ".log"))
      logs.push_back(e.path().string());
  }
  return logs.size() == 1 ? logs[0] : "";
}

bool looks_like_log(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  for (int k = 0; k < 400 && std::getline(in, line); ++k) {
    if (line.rfind("FLASER ", 0) == 0 || line.rfind("ROBOTLASER1 ", 0) == 0) return true;
  }
  return false;
}

// For each reference scan, the raw scan it corrects (see the top of the file).
std::vector<int> match_reference(const std::vector<Scan>& raw, const std::vector<Scan>& ref,
                                 const std::string& ref_path, const std::string& raw_path) {
  std::vector<double> logger(raw.size());
  std::vector<std::size_t> order(raw.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return raw[a].logger < raw[b].logger; });
  for (std::size_t k = 0; k < order.size(); ++k) logger[k] = raw[order[k]].logger;
  std::vector<int> match;
  std::vector<bool> used(raw.size(), false);
  for (const Scan& c : ref) {
    const double half = printed_half_unit(c.logger_token, c.logger);
    auto it = std::lower_bound(logger.begin(), logger.end(), c.logger - half);
    std::vector<std::size_t> near, same;
    for (; it != logger.end() && *it <= c.logger + half; ++it) {
      near.push_back(order[static_cast<std::size_t>(it - logger.begin())]);
    }
    for (std::size_t k : near) {
      if (same_ranges(raw[k], c)) same.push_back(k);
    }
    const std::vector<std::size_t>& pick = near.size() == 1 ? near : same;
    if (pick.size() != 1) {
      input_error(ref_path, c.line,
                  "timestamp " + c.logger_token + " meets " + std::to_string(near.size()) +
                      " scans of " + raw_path + " by logger_timestamp and " +
                      std::to_string(same.size()) + " of them by ranges; one was expected");
    }
    if (used[pick[0]]) {
      input_error(ref_path, c.line,
                  "corrects the scan of " + raw_path + ":" + std::to_string(raw[pick[0]].line) +
                      " a second time");
    }
    used[pick[0]] = true;
    match.push_back(static_cast<int>(pick[0]));
  }
  return match;
}

std::unique_ptr<SequenceSource> open(const std::string& dir, const SourceOptions& options) {
  const std::string path = find_log(dir);
  if (path.empty()) input_error(dir, 0, "no CARMEN log (a .clf/.log file, or a folder with one)");
  std::vector<Scan> scans = read_log(path);
  if (scans.empty()) input_error(path, 0, "no FLASER or ROBOTLASER1 line");
  std::stable_sort(scans.begin(), scans.end(),
                   [](const Scan& a, const Scan& b) { return a.stamp < b.stamp; });

  SequenceInfo info;
  info.format = "carmen";
  info.dir = dir;
  info.planar = true;
  info.recorded = static_cast<int>(scans.size());
  std::vector<Rigid<3>> reference(scans.size());
  std::vector<bool> keep(scans.size(), options.reference.empty());
  if (!options.reference.empty()) {
    require_file(options.reference, "SourceOptions::reference, a corrected CARMEN log");
    const std::vector<Scan> ref = read_log(options.reference);
    if (ref.empty()) input_error(options.reference, 0, "no FLASER or ROBOTLASER1 line");
    const std::vector<int> match = match_reference(scans, ref, options.reference, path);
    for (std::size_t j = 0; j < ref.size(); ++j) {
      const auto k = static_cast<std::size_t>(match[j]);
      keep[k] = true;
      reference[k] = planar(ref[j].x, ref[j].y, ref[j].theta);
    }
    info.poses_file = options.reference;
    info.note = "kept the " + std::to_string(ref.size()) + " of " + std::to_string(scans.size()) +
                " scans the reference corrects";
  }
  for (const Scan& s : scans) {
    info.odometry_stream_stamps.push_back(s.stamp);
    info.odometry_stream.push_back(planar(s.x, s.y, s.theta));
  }
  std::vector<Scan> kept;
  for (std::size_t k = 0; k < scans.size(); ++k) {
    if (!keep[k]) continue;
    info.stamps.push_back(scans[k].stamp);
    info.odometry.push_back(planar(scans[k].x, scans[k].y, scans[k].theta));
    if (!options.reference.empty()) info.poses.push_back(reference[k]);
    kept.push_back(std::move(scans[k]));
  }
  return std::make_unique<CarmenLog>(std::move(info), std::move(kept));
}

}  // namespace

SourceInfo carmen_source() {
  return {"carmen",
          "CARMEN log (.clf/.log, or a folder with one): FLASER or ROBOTLASER1 scans, odometry; "
          "the reference option: a corrected log",
          [](const std::string& dir) {
            const std::string log = find_log(dir);
            return !log.empty() && looks_like_log(log);
          },
          open};
}

}  // namespace verifybench::sources
