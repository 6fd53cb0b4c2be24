#pragma once
// What diagnosis/real_logs draws and puts in the findings for one diagnosed log, from public
// diagnosis functions (window_residual, negative_log_likelihood) on the same windows:
//  - per kept cause that changes the mean motion, the binned means of the residual component it
//    acts on against the covariate that reveals it, under the nominal model and with the cause
//    (e.g. along-track residual against speed for velocity_scale);
//  - the time-offset profile: deviance 2·(NLL(o) − min) of the model with every kept cause, the
//    offset o swept over a grid (the others held; noise floor of the nominal fit), with the
//    χ²₁(0.95) = 3.84 line that bounds the diagnosis's 95% interval (timed references only);
//  - the error distribution (CDF of per-window translation and heading error) of the nominal
//    model and of the model with every kept cause.
#include <string>
#include <vector>

#include "algorithms/diagnosis/diagnosis_types.h"
#include "reports/report.h"

namespace locbench::experiments {

// The findings element of one diagnosis: kept causes, their parameters' 95% intervals and gains.
reports::DiagnosedLog diagnosed_log(const std::string& log, const diagnosis::Diagnosis& d);

struct DiagnosisPlotOptions {
  std::size_t bins = 12;           // binned means per residual chart
  double offset_range = 0.3;       // profile over ±range [s]
  std::size_t offset_points = 61;  // grid points of the profile
  std::size_t cdf_points = 200;    // order statistics kept per CDF series
};

// Charts of one diagnosed log (`ds` is the plot-name-safe dataset key). Only odometry causes.
std::vector<reports::Plot> diagnosis_plots(const std::string& ds, const diagnosis::MotionData& data,
                                           const diagnosis::Diagnosis& d, const DiagnosisPlotOptions& options = {});

}  // namespace locbench::experiments
