#pragma once
// The χ² law, once for the whole tree: quantiles for validation gates (EKF, line-feature
// Kalman, agglomerative line merging), consistency intervals (NEES/NIS) and likelihood-ratio
// thresholds (diagnosis). The degrees of freedom are their own type, so a call with the
// probability and the degrees of freedom swapped does not compile.

namespace locbench {

struct ChiSquareDof {
  explicit ChiSquareDof(double dof);  // std::invalid_argument unless dof > 0
  double value;
};

// x with P(X ≤ x) = probability, X ~ χ²(dof); std::invalid_argument unless 0 ≤ probability < 1.
double chi_square_quantile(ChiSquareDof dof, double probability);
// x with P(X > x) = tail (computed on the complement: accurate for tiny tails).
double chi_square_upper_quantile(ChiSquareDof dof, double tail);
// P(X > x); 1 for x ≤ 0.
double chi_square_upper_tail(ChiSquareDof dof, double x);

}  // namespace locbench
