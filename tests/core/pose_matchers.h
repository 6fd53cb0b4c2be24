#pragma once
#include <gmock/gmock.h>

#include <cmath>

#include "core/angle.h"
#include "core/pose2.h"

namespace locbench::testing {

// Matches a Pose2 within `eps` in x, y and (wrapped) θ.
MATCHER_P2(IsNearlyPose, expected, eps, "") {
  return std::abs(arg.x - expected.x) <= eps && std::abs(arg.y - expected.y) <= eps &&
         std::abs(angle_diff(arg.theta, expected.theta)) <= eps;
}

}  // namespace locbench::testing
