#include "datasets/io/tum_writer.h"

#include <cmath>
#include <stdexcept>

#include "datasets/io/number_format.h"
#include "datasets/io/text_writer.h"

namespace locbench::io {

std::string format_tum(const Trajectory& trajectory) {
  std::string out = "# timestamp x y z qx qy qz qw\n";
  const auto& poses = trajectory.poses();
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const StampedPose& p = poses[i];
    if (!std::isfinite(p.t) || !std::isfinite(p.pose.x) || !std::isfinite(p.pose.y) || !std::isfinite(p.pose.theta)) {
      throw std::invalid_argument("write_tum: pose " + std::to_string(i) + " has a non-finite value");
    }
    // Planar pose: z = 0 and the quaternion of a rotation about z, (0, 0, sin θ/2, cos θ/2).
    append_row(out,
               {p.t, p.pose.x, p.pose.y, 0.0, 0.0, 0.0, std::sin(0.5 * p.pose.theta), std::cos(0.5 * p.pose.theta)});
  }
  return out;
}

void write_tum(const Trajectory& trajectory, const std::filesystem::path& path) {
  write_text_file(path, format_tum(trajectory));
}

}  // namespace locbench::io
