#pragma once
// The residual battery of the landmark channel: range and bearing residuals of a model, each
// standardized by the model's own scale, tested for a bias, dependence on the predicted range
// (a scale), variance growing with range, heavy tails, lead/lag against the true turn rate (a
// time offset), and per-landmark means that differ (a landmark whose surveyed position is off).
#include <vector>

#include "algorithms/diagnosis/landmark_model.h"
#include "algorithms/diagnosis/residual_tests.h"

namespace locbench::diagnosis {

// The residual names the tests carry (and the catalog's `explains` use).
inline constexpr const char* kLandmarkRange = "landmark_range";
inline constexpr const char* kLandmarkBearing = "landmark_bearing";

// Tests on the observations `index` whose geometry is valid (`geometry` at m.time_offset).
std::vector<ResidualTest> landmark_battery(const LandmarkData& d, const std::vector<LandmarkGeometry>& geometry,
                                           const LandmarkModel& m, const std::vector<std::size_t>& index);

// Do the per-landmark means of standardized residuals z differ? Σ_k n_k·(z̄_k − z̄)² ~ χ²_{K−1}
// under a common mean and unit variance (one-way analysis of variance with known variance);
// landmarks with fewer than 5 observations are pooled out.
ResidualTest landmark_dependence_test(const std::vector<double>& z, const std::vector<int>& landmark,
                                      const std::string& residual);

}  // namespace locbench::diagnosis
