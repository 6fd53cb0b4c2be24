// Histogram diagnosis at scale: thousands of bins neither crash nor give non-finite fits, and counts that are not
// whole, too large or all in one bin are input errors.
#include <gtest/gtest.h>

#include <cmath>

#include "algorithms/diagnosis/diagnosis.h"
#include "core/errors.h"
#include "core/units.h"
#include "diagnosis_test_helpers.h"

namespace locbench::diagnosis {
namespace {

// `bins` 1° bins centred on 0; the central `filled` hold rounded N(0, 3°) counts of 800 samples
// per 10 bins' worth of spread.
ResidualHistogram padded(int bins, int filled) {
  ResidualHistogram h{"r", "deg", {}, {}};
  for (int i = 0; i <= bins; ++i) h.edges.push_back(deg(i - bins / 2));
  for (int i = 0; i < bins; ++i) {
    const int k = i - bins / 2;
    h.counts.push_back(2 * std::abs(k) < filled ? std::round(400.0 * std::exp(-0.5 * k * k / 9.0)) + 1.0 : 0.0);
  }
  return h;
}

TEST(HistogramScale, TenThousandBinsWithTenFilledAreDiagnosedNotCrashed) {
  // The issue's reproduction: ±5000 bins, Table 3.1's counts in the middle.
  ResidualHistogram h{"r", "deg", {}, {}};
  for (int i = -5000; i <= 5000; ++i) h.edges.push_back(deg(i));
  h.counts.assign(10000, 0.0);
  const double t31[] = {3, 15, 5, 177, 20, 419, 11, 139, 7, 13};
  for (int i = 0; i < 10; ++i) h.counts[4995 + i] = t31[i];
  const Diagnosis d = diagnose_histogram(h, "padded");
  EXPECT_EQ(d.detected, std::vector<std::string>{"compass_quantization"}) << d.verdict;
}

TEST(HistogramScale, ZeroPaddingDoesNotChangeTheLatticeStep) {
  ResidualHistogram h{"r", "deg", {}, {}};
  for (int i = -5; i <= 5; ++i) h.edges.push_back(deg(i));
  h.counts = {3, 15, 5, 177, 20, 419, 11, 139, 7, 13};
  ResidualHistogram wide{"r", "deg", {}, {}};
  for (int i = -180; i <= 180; ++i) wide.edges.push_back(deg(i));
  wide.counts.assign(360, 0.0);
  for (int i = 0; i < 10; ++i) wide.counts[175 + i] = h.counts[i];
  const double step = diagnose_histogram(h, "h").causes.front().parameters.front().value;
  const double wide_step = diagnose_histogram(wide, "wide").causes.front().parameters.front().value;
  EXPECT_NEAR(to_deg(wide_step), to_deg(step), 0.05);
}

// Its time is measured, not asserted: BM_DiagnoseHistogram/filled_bins:{50,200,500} (the NLL is
// linear in the bins; 200 bins once took 40 s with quadratic lattice sums).
TEST(HistogramScale, TwoHundredFilledBinsAreDiagnosedWithFiniteFits) {
  const Diagnosis d = diagnose_histogram(padded(200, 200), "h");
  EXPECT_FALSE(d.verdict.empty());
  for (const auto& c : d.causes)
    for (const auto& p : c.parameters) EXPECT_TRUE(std::isfinite(p.value)) << c.id << " " << p.name;
}

TEST(HistogramScale, CountsMustBeWholeBoundedAndSpread) {
  test_support::expect_histogram_errors({
      {R"({"residual":"r","unit":"deg","edges":[0,1,2,3,4,5],"counts":[9,9,3.5,9,9]})", "counts[2]"},
      {R"({"residual":"r","unit":"deg","edges":[0,1,2,3,4,5],"counts":[9,9,1e18,9,9]})", "limit"},
      {R"({"residual":"r","unit":"deg","edges":[0,1,2,3,4,5],"counts":[0,0,900,0,0]})", "at least 3 bins"},
      {R"({"residual":"r","unit":"deg","edges":[0,1,2,3,4,1e300],"counts":[9,9,9,9,9]})", "edges[5]"},
  });
}

}  // namespace
}  // namespace locbench::diagnosis
