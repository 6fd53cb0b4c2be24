#include "datasets/io/tum_reader.h"

#include <array>
#include <cmath>

#include "datasets/io/data_lines.h"
#include "datasets/io/number_format.h"

namespace locbench::io {
namespace {

constexpr double kNormTolerance = 1e-3;

Trajectory read_tum_lines(LineReader& reader) {
  static constexpr std::array<const char*, 8> kNames = {"timestamp", "x", "y", "z", "qx", "qy", "qz", "qw"};
  std::vector<StampedPose> poses;
  for_each_numeric_row(reader, kNames, [&](const std::array<double, 8>& v, const FieldContext& ctx) {
    const double qx = v[4], qy = v[5], qz = v[6], qw = v[7];
    const double norm = std::sqrt(qx * qx + qy * qy + qz * qz + qw * qw);
    if (!(std::abs(norm - 1.0) <= kNormTolerance)) {
      std::string msg = "expected a unit quaternion (qx qy qz qw), found norm ";
      append_number(msg, norm);
      fail_input(ctx, msg);
    }
    if (!poses.empty() && v[0] < poses.back().t) {
      fail_input(ctx, "timestamp goes back in time: times must not decrease");
    }
    const double yaw = std::atan2(2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz));
    poses.push_back({v[0], Pose2(v[1], v[2], yaw)});
  });
  return Trajectory(std::move(poses));
}

}  // namespace

Trajectory read_tum(const std::filesystem::path& path) { return read_lines_of(path, read_tum_lines); }

Trajectory parse_tum(std::string_view text, const std::string& source_name) {
  return read_lines_of(text, source_name, read_tum_lines);
}

}  // namespace locbench::io
