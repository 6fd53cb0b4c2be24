// The ML calibration on the other real data sets (skipped when absent): stachniss_ls_calib and
// grisetti_diffdrive calibrate in full; Freiburg aces and MRCLAM robot 1 are calibrated on the
// first half of each log and evaluated on the second. The numbers are printed.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <chrono>
#include <cmath>

#include "algorithms/calibration/held_out_evaluation.h"
#include "algorithms/calibration/ml_calibration.h"
#include "core/errors.h"
#include "datasets/catalog/calibration_catalog.h"
#include "datasets/catalog/data_root.h"
#include "tests/test_data.h"

namespace locbench::calibration {
using locbench::catalog::calibration_dataset_parts, locbench::catalog::dataset_catalog, locbench::catalog::DatasetEntry,
    locbench::catalog::is_calibration_dataset, locbench::catalog::load_catalog_calibration_records,
    locbench::catalog::load_catalog_dataset;
namespace {

const DatasetEntry& entry(const std::string& name) {
  for (const DatasetEntry& e : dataset_catalog()) {
    if (e.name == name) return e;
  }
  throw std::logic_error("not in the catalog: " + name);
}

void print(const MlCalibrationResult& r) {
  fmt::print("  {} samples used, {} rejected; residual RMS {:.4g} m, {:.4g} rad; χ²/dof {:.3f}\n", r.samples_used,
             r.samples_rejected, r.residual_rms_translation, r.residual_rms_rotation, r.chi2_per_dof);
  for (const CalibratedParameter& p : r.parameters) {
    fmt::print("    {:<22} {:+.6f} ± {:.6f}  (closed form {:+.6f}, nominal {:+.6f})\n", p.name, p.value,
               p.standard_error, p.closed_form, p.nominal);
  }
}

void print(const HeldOutEvaluation& h) {
  print(h.calibration);
  fmt::print(
      "  held-out {} samples, relation error RMSE nominal → calibrated: "
      "{:.4g} → {:.4g} m ({:+.1f} %), {:.4g} → {:.4g} rad ({:+.1f} %)\n",
      h.evaluation_samples, h.nominal_translation.rmse, h.calibrated_translation.rmse,
      -100.0 * h.translation_rmse_reduction, h.nominal_rotation.rmse, h.calibrated_rotation.rmse,
      -100.0 * h.rotation_rmse_reduction);
}

void expect_sound(const MlCalibrationResult& r) {
  for (const CalibratedParameter& p : r.parameters) {
    EXPECT_TRUE(std::isfinite(p.value)) << p.name;
    EXPECT_TRUE(std::isfinite(p.standard_error)) << p.name;
    EXPECT_TRUE(p.identifiable) << p.name;
  }
  EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(r.covariance).info(), Eigen::Success);
  EXPECT_TRUE(r.converged);
}

// RMSE of the relation errors of all samples under `p`: (translation, rotation).
std::pair<double, double> rmse(const CalibrationData& d, const ModelParameters& p) {
  const PoseErrors e = relative_motion_errors(d, p);
  return {error_statistics(e.translation).rmse, error_statistics(e.rotation).rmse};
}

// Scan-matched references: per-component noise (as for Censi's data).
MlCalibrationOptions scan_matched() {
  MlCalibrationOptions o;
  o.noise.kind = NoiseModelKind::kPerComponent;
  o.estimate_rotation_per_distance = true;
  return o;
}

TEST(CalibrationCatalog, NamesTheCalibrationDataSetsAndTheirParts) {
  EXPECT_TRUE(is_calibration_dataset(entry("censi_khepera")));
  EXPECT_TRUE(is_calibration_dataset(entry("stachniss_ls_calib")));
  EXPECT_FALSE(is_calibration_dataset(entry("aces")));
  const auto parts = calibration_dataset_parts(entry("censi_khepera"));
  ASSERT_EQ(parts.size(), 8u);
  EXPECT_EQ(parts[0], "lstraight");
  EXPECT_EQ(parts[7], "l90_2");
  EXPECT_EQ(calibration_dataset_parts(entry("grisetti_diffdrive")), std::vector<std::string>{""});
  EXPECT_THROW(
      calibration::calibration_data_from_records(load_catalog_calibration_records(entry("aces"), catalog::data_root())),
      UsageError);
  EXPECT_THROW(calibration::calibration_data_from_records(
                   load_catalog_calibration_records(entry("censi_khepera"), catalog::data_root(), "l45")),
               UsageError);
  try {
    load_catalog_dataset(entry("censi_khepera"), catalog::data_root());
    ADD_FAILURE() << "a calibration data set loaded as a log";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("load_catalog_calibration_records"), std::string::npos);
  }
}

TEST(CalibrationCatalog, LoadsEveryCensiPartWithItsSampleCount) {
  LOCBENCH_REQUIRE_DATA("calibration/censi_khepera");
  const std::vector<std::pair<std::string, std::size_t>> counts = {
      {"lstraight", 4396}, {"lstraight_0", 1466}, {"lstraight_1", 1465}, {"lstraight_2", 1465},
      {"l90", 3295},       {"l90_0", 1099},       {"l90_1", 1098},       {"l90_2", 1098}};
  for (const auto& [part, n] : counts) {
    const CalibrationData d = calibration::calibration_data_from_records(
        load_catalog_calibration_records(entry("censi_khepera"), catalog::data_root(), part));
    EXPECT_EQ(d.samples.size(), n) << part;
    EXPECT_NE(d.source.find(part + ".tuple"), std::string::npos) << d.source;
  }
}

// A catalog set calibrated against its scan-matched reference (printed, checked sound), with the
// relation-error RMSE (m, rad) of the nominal and of the calibrated model.
struct ScanMatchedFit {
  std::pair<double, double> before, after;
};
ScanMatchedFit calibrate_against_scan_matching(const std::string& dataset) {
  const CalibrationData d = calibration::calibration_data_from_records(
      load_catalog_calibration_records(entry(dataset), catalog::data_root()));
  const MlCalibrationResult r = calibrate_ml(d, scan_matched());
  fmt::print("{}:\n", dataset);
  print(r);
  expect_sound(r);
  const ScanMatchedFit fit{rmse(d, nominal_parameters(d)), rmse(d, r.estimate)};
  fmt::print("  relation error RMSE nominal → calibrated: {:.5g} → {:.5g} m, {:.5g} → {:.5g} rad\n", fit.before.first,
             fit.after.first, fit.before.second, fit.after.second);
  return fit;
}

TEST(MlCalibrationRealData, StachnissOdometryCalibratesAndFitsItsScanMatchedMotionsBetter) {
  LOCBENCH_REQUIRE_DATA("calibration/stachniss_ls_calib");
  const auto [before, after] = calibrate_against_scan_matching("stachniss_ls_calib");
  EXPECT_LT(after.second, before.second);
  EXPECT_LE(after.first, before.first * 1.001);
}

TEST(MlCalibrationRealData, GrisettiTicksCalibrateAndFitTheirReferenceMuchBetter) {
  LOCBENCH_REQUIRE_DATA("calibration/grisetti_diffdrive");
  const auto [before, after] = calibrate_against_scan_matching("grisetti_diffdrive");
  // The nominal model is a guess (1 m per tick unit, B = 1 m): the calibration halves the errors.
  EXPECT_LT(after.first, 0.7 * before.first);
  EXPECT_LT(after.second, 0.7 * before.second);
}

TEST(MlCalibrationRealData, AcesCalibratedOnTheFirstHalfIsEvaluatedOnTheSecond) {
  LOCBENCH_REQUIRE_DATA("slam_benchmark/clf/aces.from_bag.clf.gz");
  const Log log = load_catalog_dataset(entry("aces"), catalog::data_root());
  // Relations between nearby scans only (≤ 10 s apart): the loop-closing ones span minutes.
  RelationSampleOptions local;
  local.max_duration = 10.0;
  const CalibrationData d = calibration_data_from_relations(log, local);
  MlCalibrationOptions o;  // odometry-propagated noise with the reference noise estimated
  o.estimate_rotation_per_distance = true;
  const HeldOutEvaluation h = evaluate_held_out(d, o);
  fmt::print("aces ({} local relations):\n", d.samples.size());
  print(h);
  expect_sound(h.calibration);
  EXPECT_GT(h.evaluation_samples, 500u);
  EXPECT_TRUE(std::isfinite(h.calibrated_translation.rmse));
}

TEST(MlCalibrationRealData, MrclamRobot1CalibratedOnTheFirstHalfIsEvaluatedOnTheSecond) {
  LOCBENCH_REQUIRE_DATA("mrclam/MRCLAM_Dataset6");
  const Log log = load_catalog_dataset(entry("mrclam6_robot1"), catalog::data_root());
  SampleIntervalOptions intervals;
  intervals.odometry_time_offset = 0.25;  // the velocities lead the Vicon motion
  const CalibrationData d = calibration_data_from_velocities(log, intervals);
  MlCalibrationOptions o;
  o.noise.kind = NoiseModelKind::kPerComponent;
  const HeldOutEvaluation h = evaluate_held_out(d, o);
  fmt::print("mrclam6 robot 1 ({} samples of ≤ 0.5 m, 0.5 rad, 5 s):\n", d.samples.size());
  print(h);
  expect_sound(h.calibration);
  EXPECT_TRUE(std::isfinite(h.calibrated_rotation.rmse));
}

}  // namespace
}  // namespace locbench::calibration
