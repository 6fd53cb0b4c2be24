// The diagnosis report (locbench.diagnosis/1) against its schema, reports/diagnosis.schema.json.
#include <gtest/gtest.h>

#include <limits>

#include "algorithms/diagnosis/diagnosis.h"
#include "datasets/diagnosis/physical_log_generator.h"
#include "reports/schema_validation.h"

namespace locbench::diagnosis {
namespace {

std::string joined(const std::vector<std::string>& errors) {
  std::string s;
  for (const auto& e : errors) s += e + "\n";
  return s;
}

TEST(DiagnosisJson, AReportOfAnOffsetLogIsValidAndCarriesTheOffsetWithItsInterval) {
  sim::PhysicalEffects e;
  e.odometry_time_offset = -0.2;
  sim::PhysicalOptions o;
  o.duration = 120.0;
  const nlohmann::json j = to_json(diagnose_log(sim::generate_physical_log(e, 5, o)));
  EXPECT_TRUE(reports::validate_diagnosis_json(j).empty()) << joined(reports::validate_diagnosis_json(j));
  bool found = false;
  for (const auto& c : j["causes"]) {
    if (c["id"] != "sensor_time_offset") continue;
    found = true;
    EXPECT_TRUE(c["detected"].get<bool>());
    EXPECT_NEAR(c["parameters"]["offset_s"]["value"].get<double>(), -0.2, 0.02);
    EXPECT_LT(c["parameters"]["offset_s"]["ci95"][0].get<double>(),
              c["parameters"]["offset_s"]["ci95"][1].get<double>());
  }
  EXPECT_TRUE(found);
  EXPECT_GT(j["noise_floor"]["sigma_x_m"].get<double>(), 0.0);
}

TEST(DiagnosisJson, AHistogramDiagnosisIsValidWithItsOwnNominalModel) {
  ResidualHistogram h{"r", "deg", {}, {}};
  for (int i = -5; i <= 5; ++i) h.edges.push_back(0.017453292519943295 * i);
  for (double c : {3, 15, 51, 117, 176, 176, 117, 51, 15, 3}) h.counts.push_back(c);
  const nlohmann::json j = to_json(diagnose_histogram(h, "normal"));
  EXPECT_TRUE(reports::validate_diagnosis_json(j).empty()) << joined(reports::validate_diagnosis_json(j));
  EXPECT_EQ(j["nominal_model"]["residual"], "r");
  EXPECT_FALSE(j["nominal_model"].contains("odometry"));
}

TEST(DiagnosisJson, NonFiniteNumbersBecomeNullAndUnexplainedStructureCarriesItsReason) {
  Diagnosis d;
  d.log = "x";
  d.reference = "TRUEPOS";
  d.nominal_model = {{"odometry", "encoder"}, {"noise", "white"}};
  d.verdict = "v";
  Cause c{"velocity_scale", "odometry", false};
  c.parameters.push_back(
      {"scale", 1.0, -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()});
  d.causes.push_back(c);
  d.unexplained.push_back({"bias", "along_track", "", 7.3, 1e-12, 0.3, "velocity_scale would account for it, but …"});
  const nlohmann::json j = to_json(d);
  EXPECT_TRUE(j["causes"][0]["parameters"]["scale"]["ci95"][0].is_null());
  EXPECT_EQ(j["unexplained"][0]["reason"], "velocity_scale would account for it, but …");
  EXPECT_TRUE(reports::validate_diagnosis_json(j).empty()) << joined(reports::validate_diagnosis_json(j));
  nlohmann::json broken = j;
  broken["causes"][0]["id"] = "made_up_cause";
  EXPECT_FALSE(reports::validate_diagnosis_json(broken).empty());
}

}  // namespace
}  // namespace locbench::diagnosis
