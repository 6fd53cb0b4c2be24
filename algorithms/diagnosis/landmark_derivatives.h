#pragma once
// The exact gradient and Hessian of the landmark channel's likelihood (landmark_nll in
// landmark_model.h) with respect to the fitted model fields, by second-order forward-mode
// differentiation (hyper_dual.h) of the same formulas. The channel's damped Newton (ml_fit.h) uses
// them instead of central differences.
//
// The formulas mirror landmark_model.cpp; a change there must be made here too
// (landmark_derivatives_test.cpp checks value, gradient and Hessian against the plain likelihood
// and its central differences for every landmark cause's parameters).
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "algorithms/diagnosis/landmark_model.h"

namespace locbench::diagnosis {

// The most fields one call differentiates; more → nullopt.
inline constexpr int kMaxLandmarkDifferentiatedFields = 12;

// Fills `gradient` and `hessian` of landmark_nll(d, geometry, m, index) with respect to
// m.*fields[i] (i in fields' order) and returns the likelihood's value. Returns nullopt, with
// nothing filled, where central differences must serve: a field that is not differentiable here
// (the time offset: it is profiled), too many fields, a σ_r² below the likelihood's floor of 1e-12
// where the likelihood uses it alone (a reading the truth does not cover, or no range noise slope),
// or a model the likelihood rejects (+inf).
std::optional<double> landmark_nll_derivatives(const LandmarkData& d, const std::vector<LandmarkGeometry>& geometry,
                                               const LandmarkModel& m, const std::vector<std::size_t>& index,
                                               const std::vector<double LandmarkModel::*>& fields,
                                               Eigen::VectorXd& gradient, Eigen::MatrixXd& hessian);

}  // namespace locbench::diagnosis
