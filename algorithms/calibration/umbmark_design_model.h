#pragma once
// A deterministic measurement model of the UMBmark experiment (§2.1) and what its measurements
// can identify.
//
// Model: the robot drives the bidirectional square commanded in encoder counts computed from its
// nominal model — a straight leg of L gives each wheel round(L / c_nominal) counts, a 90°
// on-the-spot turn ∓round((π/2)·(B_nominal/2) / c_nominal) — exactly as datasets/sim does; each
// wheel then really travels counts × true metres per tick, and the true pose follows the exact
// arc of those travels over the true wheelbase. The robot's odometry integrates the same counts
// with the nominal model (also along exact arcs). The predicted return error is Borenstein's
// ε = true end − odometry end in the start frame, no noise, no slip.
//
// The true robot is parametrised by the error sources (eq. 2.1, 2.2, 2.16):
// E_d = D_R/D_L, E_b = B/B_nominal, E_o = D_a/D_n with D_a = (D_L + D_R)/2, D_n the mean nominal
// diameter, so D_L = 2·E_o·D_n/(E_d + 1), D_R = E_d·D_L, B = E_b·B_nominal.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "algorithms/calibration/identifiability.h"
#include "core/robot_params.h"

namespace locbench::calibration {

struct UmbmarkErrorParams {
  double E_d = 1.0;  // D_R/D_L (2.1)
  double E_b = 1.0;  // B_actual/B_nominal (2.2)
  double E_o = 1.0;  // D_a/D_n (2.16; E_s of 2.15)
};

// The true geometry those error sources describe around `nominal`.
WheelGeometry true_geometry(const WheelGeometry& nominal, const UmbmarkErrorParams& e);
// And back: the error sources of `actual` relative to `nominal`.
UmbmarkErrorParams error_params(const WheelGeometry& nominal, const WheelGeometry& actual);

struct UmbmarkDesignOptions {
  // Round the commanded counts to whole ticks as a real robot (and datasets/sim) must. Off: the
  // ideal square of the method's derivation (the nominal square closes exactly).
  bool quantize_counts = true;
  // Trilobot limitation (datasets/sim DriveConfig::equal_wheel_ticks): both wheels get the
  // rounded mean count.
  bool equal_wheel_ticks = false;
};

struct UmbmarkPrediction {
  Eigen::Vector2d cw = Eigen::Vector2d::Zero();   // return error of a clockwise run [m]
  Eigen::Vector2d ccw = Eigen::Vector2d::Zero();  // … of a counter-clockwise run [m]
  double heading_cw = 0.0;                        // true − odometry end heading [rad]
  double heading_ccw = 0.0;
  // The counts commanded (and logged) on a straight leg and on a 90° turn (per wheel, |counts|).
  double leg_ticks_left = 0.0;
  double leg_ticks_right = 0.0;
  double turn_ticks_left = 0.0;
  double turn_ticks_right = 0.0;
  // What a tape would measure for one straight leg: the chord from its start to its end [m].
  double leg_chord = 0.0;
  // True heading change over one straight leg (the Type B angle β) and true angle of one
  // commanded 90° turn [rad].
  double leg_heading_change = 0.0;
  double turn_angle = 0.0;
};

UmbmarkPrediction predict_umbmark(const WheelGeometry& nominal, const EncoderSpec& encoder, double side_length,
                                  const UmbmarkErrorParams& truth, const UmbmarkDesignOptions& options = {});

// ---- Identifiability of the error sources from a design's measurements ----

enum class UmbmarkDesign {
  kSquare,              // CW and CCW return-error centroids only
  kSquareWithLegTicks,  // + N_L, N_R logged on a leg (the improved method's extra input)
  kSquareWithTapedLeg,  // + the true length of one straight leg measured with a tape
  kSquareWithTapedLegAndLegTicks,
};
std::string to_string(UmbmarkDesign d);

enum class UmbmarkParameterSet {
  kClassic,   // E_d, E_b; E_o taken as known (the tape-measured E_s, eq. 2.15)
  kImproved,  // E_d, E_b, E_o (eq. 2.16–2.27)
};
std::string to_string(UmbmarkParameterSet p);

struct UmbmarkIdentifiabilityOptions {
  double run_sigma = 0.02;      // per-run, per-coordinate standard deviation of a return error [m]
  int runs_per_direction = 5;   // the centroid's covariance is run_sigma²/runs
  double tape_sigma = 0.002;    // standard deviation of a tape-measured leg length [m]
  double tick_sigma = 0.5;      // of a logged count (quantization) [ticks]
  double relative_step = 1e-6;  // central-difference step on each parameter
  // A parameter the Fisher information formally determines but only with a standard error above
  // this is reported as not identifiable in practice (E's are ratios near 1; the effects UMBmark
  // corrects are ~0.1–1 %).
  double max_standard_error = 0.01;
  UmbmarkDesignOptions model{false, false};  // the ideal square by default
};

struct UmbmarkDesignFinding {
  UmbmarkDesign design = UmbmarkDesign::kSquare;
  UmbmarkParameterSet parameter_set = UmbmarkParameterSet::kImproved;
  std::vector<std::string> measurements;  // names of the rows of the Jacobian
  Eigen::MatrixXd jacobian;               // ∂measurements/∂parameters
  IdentifiabilityReport report;           // parameters in the order E_d, E_b[, E_o]
  // For each parameter the design does not determine: the extra measurement that would.
  std::vector<std::pair<std::string, std::string>> remedies;  // (parameter, measurement)
};

// The Fisher-information analysis (analyze_identifiability) of `design` for the parameters of
// `set`, with the Jacobian taken by central differences of predict_umbmark at `at`.
UmbmarkDesignFinding analyze_umbmark_design(UmbmarkDesign design, UmbmarkParameterSet set, const WheelGeometry& nominal,
                                            const EncoderSpec& encoder, double side_length,
                                            const UmbmarkErrorParams& at,
                                            const UmbmarkIdentifiabilityOptions& options = {});

}  // namespace locbench::calibration
