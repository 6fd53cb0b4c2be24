// The diagnosis of two catalog logs keeps its causes and their values to the CLI's printed
// precision (6 significant digits): the figures of the reports in the last column of the CPU table
// in algorithms/diagnosis/README.md ("A run-in smooth in τ").
// A change that moves them — a faster fit, a new cause — is a change of what the suite reports,
// to be made on purpose (and the figures here with it), never by accident. Skips without the
// Freiburg logs.
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

}  // namespace
}  // namespace locbench::diagnosis
