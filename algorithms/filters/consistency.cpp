#include "algorithms/filters/consistency.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/angle.h"
#include "core/chi_square.h"
#include "core/linear_algebra.h"

namespace locbench::filters {

double nees(const Eigen::Ref<const Eigen::VectorXd>& error, const Eigen::Ref<const Eigen::MatrixXd>& covariance) {
  if (covariance.rows() != error.size() || covariance.cols() != error.size()) {
    throw std::invalid_argument("nees: covariance and error sizes differ");
  }
  Eigen::VectorXd w;
  if (!linalg::cholesky_lower_solve(covariance, error, w)) return std::numeric_limits<double>::infinity();
  return w.squaredNorm();
}

double pose_nees(const Pose2& truth, const Eigen::Vector3d& mean, const Eigen::Matrix3d& cov) {
  const Eigen::Vector3d e(mean(0) - truth.x, mean(1) - truth.y, angle_diff(mean(2), truth.theta));
  Eigen::Vector3d w;
  if (!linalg::cholesky_lower_solve(cov, e, w)) return std::numeric_limits<double>::infinity();
  return w.squaredNorm();
}

double nis(double innovation, double innovation_variance) {
  if (!(innovation_variance > 0.0)) return std::numeric_limits<double>::infinity();
  return innovation * innovation / innovation_variance;
}

ChiSquareInterval average_chi_square_interval(int dof, int runs, double confidence) {
  if (dof < 1 || runs < 1 || !(confidence > 0.0 && confidence < 1.0)) {
    throw std::invalid_argument("average_chi_square_interval: need dof, runs >= 1, 0 < c < 1");
  }
  const double n = static_cast<double>(dof) * runs;
  const double tail = 0.5 * (1.0 - confidence);
  return {chi_square_quantile(ChiSquareDof(n), tail) / runs, chi_square_upper_quantile(ChiSquareDof(n), tail) / runs};
}

ConsistencySummary summarize_consistency(const std::vector<std::vector<double>>& per_run, int dof, double confidence) {
  if (per_run.empty() || per_run.front().empty()) {
    throw std::invalid_argument("summarize_consistency: no runs or no steps");
  }
  ConsistencySummary s;
  s.runs = per_run.size();
  s.steps = per_run.front().size();
  s.dof = dof;
  s.bounds = average_chi_square_interval(dof, static_cast<int>(s.runs), confidence);
  s.average.assign(s.steps, 0.0);
  for (const auto& run : per_run) {
    if (run.size() != s.steps) {
      throw std::invalid_argument("summarize_consistency: runs of different lengths");
    }
    for (std::size_t k = 0; k < s.steps; ++k) s.average[k] += run[k];
  }
  std::size_t inside = 0, above = 0, below = 0;
  double total = 0.0;
  for (double& a : s.average) {
    a /= static_cast<double>(s.runs);
    total += a;
    if (s.bounds.contains(a)) {
      ++inside;
    } else if (a > s.bounds.upper || std::isnan(a)) {
      ++above;
    } else {
      ++below;
    }
  }
  const double k = static_cast<double>(s.steps);
  s.fraction_inside = inside / k;
  s.fraction_above = above / k;
  s.fraction_below = below / k;
  s.time_average = total / k;
  return s;
}

}  // namespace locbench::filters
