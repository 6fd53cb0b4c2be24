#pragma once
// The exact gradient and Hessian of the odometry model's window likelihood
// (negative_log_likelihood in odometry_model.h) with respect to the fitted model fields, by
// second-order forward-mode differentiation (hyper_dual.h) of the same formulas: the window
// prediction over the fitted mean-motion fields, then the residual densities (normal or
// Student-t, slip and stall mixtures) over all fitted fields. The damped Newton of the fits
// (ml_fit.h) uses them instead of central differences.
//
// The formulas mirror odometry_model.cpp; a change there must be made here too
// (odometry_derivatives_test.cpp checks value, gradient and Hessian against the plain likelihood
// and its central differences for every cause's parameters).
#include <Eigen/Core>
#include <vector>

#include "algorithms/diagnosis/odometry_model.h"

namespace locbench::diagnosis {

// The most fields one call differentiates; more → false.
inline constexpr int kMaxDifferentiatedFields = 12;

// Fills `gradient` and `hessian` of negative_log_likelihood(d, m, index) with respect to
// m.*fields[i] (i in fields' order) and returns the likelihood's value. Returns nullopt, with
// nothing filled, when a field is not differentiable here (time_offset: it is profiled, not
// fitted by Newton), there are too many, or the model has drive stalls on a compass reference.
// `cache` (optional, belonging to d) supplies the reference windows.
std::optional<double> negative_log_likelihood_derivatives(const MotionData& d, const OdometryModel& m,
                                                          const std::vector<std::size_t>& index,
                                                          const std::vector<double OdometryModel::*>& fields,
                                                          Eigen::VectorXd& gradient, Eigen::MatrixXd& hessian,
                                                          WindowCache* cache = nullptr);

}  // namespace locbench::diagnosis
