// Forward selection and the time-offset profile on functions whose answer is known.
#include <gtest/gtest.h>

#include <cmath>

#include "algorithms/diagnosis/selection.h"

namespace locbench::diagnosis {
namespace {

TEST(ForwardSelection, CausesEnterByLargestMarginAndStopWhenNoneClearsItsThreshold) {
  // NLL drops: cause 0 by 20, cause 1 by 3 (below χ² 6.63 as LR 6 < 6.63), cause 2 by 40.
  const double drop[] = {10.0, 3.0, 20.0};
  const Selection s = forward_select(
      3, 100.0, [](std::size_t) { return 6.63; },
      [&](const std::vector<std::size_t>& active) {
        double nll = 100.0;
        for (std::size_t i : active) nll -= drop[i];
        return SelectionFit{nll, true};
      });
  ASSERT_EQ(s.entered.size(), 2u);
  EXPECT_EQ(s.entered[0], 2u);  // LR 40 first
  EXPECT_EQ(s.entered[1], 0u);  // then LR 20
  EXPECT_DOUBLE_EQ(s.evidence[1].lr, 6.0);
  EXPECT_FALSE(s.evidence[1].lr >= s.evidence[1].threshold);
}

TEST(ForwardSelection, AnInadmissibleCandidateNeverEntersHoweverLargeItsRatio) {
  const Selection s = forward_select(
      1, 100.0, [](std::size_t) { return 3.84; },
      [](const std::vector<std::size_t>&) {
        return SelectionFit{0.0, false};
      });
  EXPECT_TRUE(s.entered.empty());
  EXPECT_FALSE(s.evidence[0].admissible);
}

TEST(OffsetProfile, AnOffsetBetweenTheReferenceSamplesIsFoundToAFractionOfThePeriod) {
  // A likelihood with its minimum at −0.137 s and bumps of the reference's 0.1 s period on top
  // (interpolation between samples): curvature 2000 s⁻² → a 95% half-width √(3.84/2000) = 0.044 s.
  auto nll = [](double o) { return 1000.0 * (o + 0.137) * (o + 0.137) + 0.05 * std::abs(std::sin(o * 31.4159)); };
  const OffsetProfile p = profile_offset(nll, nll, 0.1);
  EXPECT_NEAR(p.value, -0.137, 0.005);
  EXPECT_NEAR(p.lo, -0.137 - 0.0438, 0.006);
  EXPECT_NEAR(p.hi, -0.137 + 0.0438, 0.006);
  EXPECT_LE(p.step, 0.1 / 10.0 + 1e-12);
}

TEST(OffsetProfile, WithoutAProfiledLikelihoodThereIsNoInterval) {
  const OffsetProfile p = profile_offset([](double o) { return (o - 0.2) * (o - 0.2); }, {}, 0.01);
  EXPECT_NEAR(p.value, 0.2, 0.001);
  EXPECT_DOUBLE_EQ(p.lo, p.value);
  EXPECT_DOUBLE_EQ(p.hi, p.value);
}

TEST(OffsetProfile, AFlatProfileGivesAnIntervalReachingTheSearchRange) {
  const OffsetProfile p = profile_offset([](double) { return 1.0; }, [](double) { return 1.0; }, 0.01);
  EXPECT_DOUBLE_EQ(p.lo, -0.5);
  EXPECT_DOUBLE_EQ(p.hi, 0.5);
}

TEST(OffsetResolution, OffsetsUpToFiveMillisecondsAreNotResolved) {
  EXPECT_FALSE(offset_resolved(0.005));
  EXPECT_FALSE(offset_resolved(-0.004));
  EXPECT_TRUE(offset_resolved(-0.006));
}

}  // namespace
}  // namespace locbench::diagnosis
