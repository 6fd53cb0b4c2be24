// The catalog is the one place a cause is defined: every entry is complete, applies where its
// model does, and the report's schema knows every id.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "algorithms/diagnosis/cause_catalog.h"
#include "reports/schema_validation.h"

namespace locbench::diagnosis {
namespace {

TEST(CauseCatalog, EveryCauseHasParametersWithUnitsAnExplanationAndAnIdTheSchemaKnows) {
  const auto schema = nlohmann::json::parse(reports::diagnosis_schema_text());
  const auto ids = schema["properties"]["causes"]["items"]["properties"]["id"]["enum"];
  for (const auto& c : cause_catalog()) {
    EXPECT_FALSE(c.params.empty()) << c.id;
    for (const auto& p : c.params) EXPECT_FALSE(p.unit.empty()) << c.id << "." << p.name;
    Cause filled{std::string(c.id), std::string(c.channel), true};
    for (const auto& p : c.params) filled.parameters.push_back({p.name, 1.0, 0.9, 1.1});
    EXPECT_NE(explain(filled).find("1 [0.9, 1.1]"), std::string::npos) << c.id << ": " << explain(filled);
    EXPECT_NE(std::find(ids.begin(), ids.end(), std::string(c.id)), ids.end()) << c.id;
  }
  EXPECT_THROW(cause_spec("no_such_cause"), std::logic_error);
}

TEST(CauseCatalog, VelocityCausesApplyToVelocityOdometryAndEncoderCausesToCounts) {
  MotionData velocity;
  velocity.odometry = OdometryKind::kPose;
  velocity.reference = ReferenceKind::kTruePose;
  MotionData encoder = velocity;
  encoder.odometry = OdometryKind::kEncoder;
  auto ids = [](const MotionData& d) {
    std::vector<std::string> v;
    for (const auto* c : odometry_causes(d)) v.emplace_back(c->id);
    return v;
  };
  const auto v = ids(velocity), e = ids(encoder);
  EXPECT_NE(std::find(v.begin(), v.end(), "drive_response"), v.end());
  EXPECT_EQ(std::find(v.begin(), v.end(), "wheelbase_scale"), v.end());
  EXPECT_NE(std::find(e.begin(), e.end(), "wheelbase_scale"), e.end());
  EXPECT_EQ(std::find(e.begin(), e.end(), "velocity_scale"), e.end());
  // Relations carry the odometry's clock: no time offset to find.
  velocity.reference = ReferenceKind::kRelations;
  const auto r = ids(velocity);
  EXPECT_EQ(std::find(r.begin(), r.end(), "sensor_time_offset"), r.end());
}

TEST(CauseCatalog, ANoiseCauseAccountsForTheShapeTestsItNames) {
  const CauseSpec& t = cause_spec(cause::kHeavyTails);
  EXPECT_TRUE(t.noise);
  EXPECT_TRUE(accounts_for(t, ResidualTest{"heavy_tails", "heading"}));
  EXPECT_FALSE(accounts_for(t, ResidualTest{"bias", "heading"}));
  EXPECT_TRUE(accounts_for(cause_spec(cause::kVelocityScale), ResidualTest{"bias", "along_track"}));
}

}  // namespace
}  // namespace locbench::diagnosis
