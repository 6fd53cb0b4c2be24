// The independent scale checks set beside a kept velocity scale.
#include "algorithms/diagnosis/scale_checks.h"

#include <gtest/gtest.h>

namespace locbench::diagnosis {
namespace {

TEST(ScaleDisagreement, AScaleWhoseIntervalMeetsTheChecksSaysNothing) {
  ScaleChecks c;
  c.path_length_ratio = 0.936;
  c.ls_velocity_scale = 0.925;
  c.median_window_ratio = 0.99;
  // MRCLAM robot 2: 0.933 [0.918, 0.947] against checks 0.925–0.936.
  EXPECT_EQ(scale_disagreement("robot2", 0.933, 0.918, 0.947, c), "");
  // Touching the widened range [0.905, 0.956] is agreement too.
  EXPECT_EQ(scale_disagreement("x", 0.97, 0.956, 0.98, c), "");
}

TEST(ScaleDisagreement, AScaleOutsideTheChecksNamesTheSkewWhenTheMedianDiffers) {
  ScaleChecks c;
  c.path_length_ratio = 0.955;
  c.ls_velocity_scale = 0.950;
  c.median_window_ratio = 1.014;
  // MRCLAM robot 1: Student-t scale 0.999 [0.987, 1.011]; range [0.930, 0.975].
  const std::string s = scale_disagreement("robot1", 0.999, 0.987, 1.011, c);
  EXPECT_NE(s.find("outside the independent checks' range ±0.02 ([0.930, 0.975])"), std::string::npos) << s;
  EXPECT_NE(s.find("skewed (median 1.014, path-length ratio 0.955)"), std::string::npos) << s;
  c.median_window_ratio = 0.96;
  EXPECT_EQ(scale_disagreement("robot1", 0.999, 0.987, 1.011, c).find("skewed"), std::string::npos);
}

}  // namespace
}  // namespace locbench::diagnosis
