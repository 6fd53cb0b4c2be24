#pragma once
// Filter consistency (Bar-Shalom, Li & Kirubarajan, "Estimation with Applications to Tracking
// and Navigation", 2001, §5.4): the normalised estimation error squared NEES = eᵀP⁻¹e and the
// normalised innovation squared NIS = ν²/S. For a consistent filter the average of NEES over N
// independent runs at one time step, times N, is χ² with N·n degrees of freedom (n = state
// dimension, or measurement dimension for the NIS); its two-sided bounds follow from the χ²
// quantiles (Boost.Math).
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "core/pose2.h"

namespace locbench::filters {

// eᵀP⁻¹e; +∞ when P is not positive definite (a zero error with singular P gives +∞ too: a
// filter claiming certainty is not consistent).
double nees(const Eigen::Ref<const Eigen::VectorXd>& error, const Eigen::Ref<const Eigen::MatrixXd>& covariance);
// NEES of a pose estimate [x, y, θ] against the truth, heading error wrapped to [−π, π).
double pose_nees(const Pose2& truth, const Eigen::Vector3d& mean, const Eigen::Matrix3d& cov);
// ν²/S for a scalar innovation; +∞ when S <= 0.
double nis(double innovation, double innovation_variance);

// Two-sided interval of the N-run average of a χ²(dof) statistic: [χ²_{(1−c)/2}(N·dof)/N,
// χ²_{(1+c)/2}(N·dof)/N].
struct ChiSquareInterval {
  double lower = 0.0;
  double upper = 0.0;
  bool contains(double v) const { return v >= lower && v <= upper; }
};
ChiSquareInterval average_chi_square_interval(int dof, int runs, double confidence = 0.95);

// Per-step N-run average of NEES (or NIS) series and how often it lies inside the interval.
struct ConsistencySummary {
  std::size_t runs = 0;
  std::size_t steps = 0;
  int dof = 0;
  ChiSquareInterval bounds;
  std::vector<double> average;   // per step, over runs
  double fraction_inside = 0.0;  // of steps whose average lies inside the bounds
  double fraction_above = 0.0;   // above the upper bound (over-confident)
  double fraction_below = 0.0;   // below the lower bound (conservative)
  double time_average = 0.0;     // mean of `average` over steps
};
// `per_run[r][k]` = statistic of run r at step k; all runs must have the same length (throws
// std::invalid_argument otherwise, or when empty).
ConsistencySummary summarize_consistency(const std::vector<std::vector<double>>& per_run, int dof,
                                         double confidence = 0.95);

}  // namespace locbench::filters
