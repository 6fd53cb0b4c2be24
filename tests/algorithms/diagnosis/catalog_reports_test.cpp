// The diagnosis of every real catalog log (the three Freiburg logs and MRCLAM Dataset 6's five
// robots) keeps its causes and their values to the CLI's printed precision (6 significant
// digits): the figures of the reports in the last column of the CPU table in
// algorithms/diagnosis/README.md ("A run-in smooth in τ").
// A change that moves them — a faster fit, a new cause — is a change of what the suite reports,
// to be made on purpose (and the figures here with it), never by accident. Each skips without
// its logs.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "algorithms/diagnosis/diagnosis.h"
#include "datasets/catalog/dataset_catalog.h"
#include "tests/test_data.h"

namespace locbench::diagnosis {
namespace {

struct Expected {
  std::string cause, parameter;
  double value;
};

void expect_report(const std::string& dataset, const std::vector<std::string>& detected,
                   const std::vector<Expected>& values) {
  const Log log = catalog::load_catalog_dataset(*catalog::find_dataset(dataset), catalog::data_root());
  const Diagnosis d = diagnose_log(log, DiagnosisOptions{});
  EXPECT_EQ(d.detected, detected);
  for (const Expected& e : values) {
    SCOPED_TRACE(e.cause + "." + e.parameter);
    bool found = false;
    for (const Cause& c : d.causes) {
      if (c.id != e.cause) continue;
      for (const Estimate& p : c.parameters) {
        if (p.name != e.parameter) continue;
        found = true;
        EXPECT_NEAR(p.value, e.value, 5e-6 * std::abs(e.value));  // the 6th significant digit
      }
    }
    EXPECT_TRUE(found);
  }
}

TEST(DiagnosisOfTheCatalogLogs, AcesKeepsItsCausesAndValuesToSixDigits) {
  LOCBENCH_REQUIRE_DATA("slam_benchmark");
  expect_report("aces", {"drive_response", "turn_rate_bias", "turn_rate_scale", "heavy_tailed_noise"},
                {{"drive_response", "tau_s", 0.0810638},
                 {"turn_rate_bias", "bias_rad_s", -0.00143453},
                 {"turn_rate_scale", "scale", 1.01177},
                 {"heavy_tailed_noise", "dof", 1.55538}});
}

TEST(DiagnosisOfTheCatalogLogs, IntelKeepsItsCausesAndValuesToSixDigits) {
  LOCBENCH_REQUIRE_DATA("slam_benchmark");
  expect_report("intel", {"drive_stall", "turn_rate_scale", "heavy_tailed_noise"},
                {{"drive_stall", "rate_per_s", 0.143839},
                 {"drive_stall", "duration_s", 0.44758},
                 {"turn_rate_scale", "scale", 0.956197},
                 {"heavy_tailed_noise", "dof", 1.5045}});
}

TEST(DiagnosisOfTheCatalogLogs, MitCsailKeepsItsCausesAndValuesToSixDigits) {
  LOCBENCH_REQUIRE_DATA("slam_benchmark");
  expect_report("mit_csail", {"drive_response", "heavy_tailed_noise"},
                {{"drive_response", "tau_s", 0.170073}, {"heavy_tailed_noise", "dof", 2.67595}});
}

TEST(DiagnosisOfTheCatalogLogs, MrclamRobot1KeepsItsCausesAndValuesToSixDigits) {
  LOCBENCH_REQUIRE_DATA("mrclam");
  expect_report("mrclam6_robot1",
                {"sensor_time_offset", "drive_stall", "turn_rate_scale", "odometry_noise_growth", "heavy_tailed_noise",
                 "landmark_range_scale", "landmark_range_bias", "landmark_range_off_axis_scale", "landmark_time_offset",
                 "landmark_range_dependent_noise", "landmark_turn_dependent_bearing_noise", "landmark_position_error",
                 "landmark_heavy_tails"},
                {{"sensor_time_offset", "offset_s", -0.246308},
                 {"drive_stall", "duration_s", 0.366218},
                 {"drive_stall", "rate_per_s", 0.143413},
                 {"turn_rate_scale", "scale", 0.934028},
                 {"odometry_noise_growth", "k2_m", 5.88735e-05},
                 {"heavy_tailed_noise", "dof", 2.97199},
                 {"landmark_range_scale", "scale", 1.0154},
                 {"landmark_range_bias", "bias_m", 0.031176},
                 {"landmark_range_off_axis_scale", "per_rad", 0.0125052},
                 {"landmark_range_off_axis_scale", "per_rad2", -0.469295},
                 {"landmark_time_offset", "offset_s", 0.0501558},
                 {"landmark_range_dependent_noise", "slope", 0.00602366},
                 {"landmark_turn_dependent_bearing_noise", "slope", 0.0351321},
                 {"landmark_position_error", "dx_m", -0.0647414},
                 {"landmark_position_error", "dy_m", -0.00563929},
                 {"landmark_heavy_tails", "dof", 3.39366}});
}

TEST(DiagnosisOfTheCatalogLogs, MrclamRobot2KeepsItsCausesAndValuesToSixDigits) {
  LOCBENCH_REQUIRE_DATA("mrclam");
  expect_report("mrclam6_robot2",
                {"drive_response", "drive_stall", "turn_rate_scale", "odometry_noise_growth", "heavy_tailed_noise",
                 "landmark_range_scale", "landmark_range_bias", "landmark_range_off_axis_scale",
                 "landmark_bearing_bias", "landmark_time_offset", "landmark_range_dependent_noise",
                 "landmark_turn_dependent_bearing_noise", "landmark_position_error", "landmark_heavy_tails"},
                {{"drive_response", "tau_s", 0.2416},
                 {"drive_stall", "duration_s", 0.345086},
                 {"drive_stall", "rate_per_s", 0.202736},
                 {"turn_rate_scale", "scale", 0.920263},
                 {"odometry_noise_growth", "k2_m", 5.1413e-05},
                 {"heavy_tailed_noise", "dof", 5.51601},
                 {"landmark_range_scale", "scale", 1.05128},
                 {"landmark_range_bias", "bias_m", -0.00128579},
                 {"landmark_range_off_axis_scale", "per_rad", 0.0128335},
                 {"landmark_range_off_axis_scale", "per_rad2", -0.50665},
                 {"landmark_bearing_bias", "bias_rad", 0.00263206},
                 {"landmark_time_offset", "offset_s", 0.0339686},
                 {"landmark_range_dependent_noise", "slope", 0.00607354},
                 {"landmark_turn_dependent_bearing_noise", "slope", 0.0347553},
                 {"landmark_position_error", "dx_m", 0.00276866},
                 {"landmark_position_error", "dy_m", -0.00225783},
                 {"landmark_heavy_tails", "dof", 7.26772}});
}

TEST(DiagnosisOfTheCatalogLogs, MrclamRobot3KeepsItsCausesAndValuesToSixDigits) {
  LOCBENCH_REQUIRE_DATA("mrclam");
  expect_report("mrclam6_robot3",
                {"drive_response", "drive_stall", "turn_rate_scale", "sensor_time_offset", "odometry_noise_growth",
                 "velocity_scale", "heavy_tailed_noise", "landmark_range_scale", "landmark_range_bias",
                 "landmark_range_off_axis_scale", "landmark_bearing_bias", "landmark_time_offset",
                 "landmark_range_dependent_noise", "landmark_turn_dependent_bearing_noise", "landmark_position_error",
                 "landmark_heavy_tails"},
                {{"drive_response", "tau_s", 0.156349},
                 {"drive_stall", "duration_s", 0.360371},
                 {"drive_stall", "rate_per_s", 0.147913},
                 {"turn_rate_scale", "scale", 0.888653},
                 {"sensor_time_offset", "offset_s", -0.0848002},
                 {"odometry_noise_growth", "k2_m", 2.35506e-05},
                 {"velocity_scale", "scale", 0.992583},
                 {"heavy_tailed_noise", "dof", 5.76733},
                 {"landmark_range_scale", "scale", 1.01086},
                 {"landmark_range_bias", "bias_m", 0.0406417},
                 {"landmark_range_off_axis_scale", "per_rad", 0.00264379},
                 {"landmark_range_off_axis_scale", "per_rad2", -0.469072},
                 {"landmark_bearing_bias", "bias_rad", -0.00245243},
                 {"landmark_time_offset", "offset_s", 0.0368001},
                 {"landmark_range_dependent_noise", "slope", 0.00502922},
                 {"landmark_turn_dependent_bearing_noise", "slope", 0.0269999},
                 {"landmark_position_error", "dx_m", -0.00958686},
                 {"landmark_position_error", "dy_m", 0.00810595},
                 {"landmark_heavy_tails", "dof", 2.96633}});
}

TEST(DiagnosisOfTheCatalogLogs, MrclamRobot4KeepsItsCausesAndValuesToSixDigits) {
  LOCBENCH_REQUIRE_DATA("mrclam");
  expect_report("mrclam6_robot4",
                {"drive_response", "odometry_noise_growth", "turn_rate_scale", "sensor_time_offset", "velocity_scale",
                 "heavy_tailed_noise", "landmark_range_bias", "landmark_range_off_axis_scale", "landmark_bearing_bias",
                 "landmark_time_offset", "landmark_range_dependent_noise", "landmark_turn_dependent_bearing_noise",
                 "landmark_position_error"},
                {{"drive_response", "tau_s", 0.168908},
                 {"odometry_noise_growth", "k2_m", 3.21522e-05},
                 {"turn_rate_scale", "scale", 0.910489},
                 {"sensor_time_offset", "offset_s", -0.0646344},
                 {"velocity_scale", "scale", 0.921655},
                 {"heavy_tailed_noise", "dof", 2.22171},
                 {"landmark_range_bias", "bias_m", 0.109569},
                 {"landmark_range_off_axis_scale", "per_rad", 0.0644552},
                 {"landmark_range_off_axis_scale", "per_rad2", -0.528667},
                 {"landmark_bearing_bias", "bias_rad", -0.0141744},
                 {"landmark_time_offset", "offset_s", 0.0320001},
                 {"landmark_range_dependent_noise", "slope", 0.00811417},
                 {"landmark_turn_dependent_bearing_noise", "slope", 0.0262754},
                 {"landmark_position_error", "dx_m", -0.00645903},
                 {"landmark_position_error", "dy_m", -0.0142482}});
}

TEST(DiagnosisOfTheCatalogLogs, MrclamRobot5KeepsItsCausesAndValuesToSixDigits) {
  LOCBENCH_REQUIRE_DATA("mrclam");
  expect_report("mrclam6_robot5",
                {"drive_response", "drive_stall", "sensor_time_offset", "odometry_noise_growth", "turn_rate_scale",
                 "velocity_scale", "heavy_tailed_noise", "landmark_range_scale", "landmark_range_bias",
                 "landmark_range_off_axis_scale", "landmark_bearing_bias", "landmark_time_offset",
                 "landmark_range_dependent_noise", "landmark_turn_dependent_bearing_noise", "landmark_position_error",
                 "landmark_heavy_tails"},
                {{"drive_response", "tau_s", 0.17478},
                 {"drive_stall", "duration_s", 0.395878},
                 {"drive_stall", "rate_per_s", 0.156211},
                 {"sensor_time_offset", "offset_s", -0.145159},
                 {"odometry_noise_growth", "k2_m", 5.44138e-05},
                 {"turn_rate_scale", "scale", 0.964287},
                 {"velocity_scale", "scale", 0.999677},
                 {"heavy_tailed_noise", "dof", 4.72398},
                 {"landmark_range_scale", "scale", 1.02004},
                 {"landmark_range_bias", "bias_m", 0.0392605},
                 {"landmark_range_off_axis_scale", "per_rad", -0.0402375},
                 {"landmark_range_off_axis_scale", "per_rad2", -0.491175},
                 {"landmark_bearing_bias", "bias_rad", -7.31114e-05},
                 {"landmark_time_offset", "offset_s", 0.0352001},
                 {"landmark_range_dependent_noise", "slope", 0.00476245},
                 {"landmark_turn_dependent_bearing_noise", "slope", 0.0272596},
                 {"landmark_position_error", "dx_m", -0.00783448},
                 {"landmark_position_error", "dy_m", 0.00341419},
                 {"landmark_heavy_tails", "dof", 2.83764}});
}

}  // namespace
}  // namespace locbench::diagnosis
