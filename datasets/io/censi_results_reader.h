#pragma once
// Reader of the published solutions of Censi et al.'s calibration data sets
// (censi_khepera/*_results.json), written by their `solver`:
// {"axle", "l_diam", "r_diam", "l_x", "l_y", "l_theta", "E_d", "E_b", "covariance": 6×6}.
#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <string_view>

namespace locbench::io {

struct CensiPublishedResult {
  double axle = 0.0;            // b [m]
  double left_diameter = 0.0;   // "l_diam" = 2·r_L [m]
  double right_diameter = 0.0;  // "r_diam" = 2·r_R [m]
  double sensor_x = 0.0;        // "l_x" [m]
  double sensor_y = 0.0;        // "l_y" [m]
  double sensor_theta = 0.0;    // "l_theta" [rad]
  double E_d = 0.0;             // r_R / r_L
  double E_b = 0.0;             // axle / 0.09 m (the upstream solver's hard-coded nominal)
  // Inverse Fisher information of the upstream solver's state (r_L, r_R, b, l_x, l_y, l_θ):
  // wheel RADII, not the diameters stored beside it (solver2.cpp prints "Uncertainty r_L" from
  // entry (0, 0); calib_result2json writes l_diam = 2·radius_l).
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Zero();

  double left_radius() const { return 0.5 * left_diameter; }
  double right_radius() const { return 0.5 * right_diameter; }
  // √covariance(i, i) in the state order above.
  double standard_error(int i) const;
};

// Reads a results file (plain or gzip). All the fields above must be present and finite and
// the covariance symmetric (relative tolerance 1e-6) with a positive diagonal; other keys are
// ignored. Throws InputError naming the file, the line and the offending key.
CensiPublishedResult read_censi_results(const std::filesystem::path& path);

// The same for text in memory; `source_name` stands for the file name in errors.
CensiPublishedResult parse_censi_results(std::string_view text, const std::string& source_name);

}  // namespace locbench::io
