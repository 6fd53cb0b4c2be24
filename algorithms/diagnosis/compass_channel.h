#pragma once
// Compass readings against ground truth: residual r = wrap(reading − θ_true(t − offset)).
// Model (§3.2, the simulator's compass): reading = quantize(θ + bias + zone bias + N(0, σ²)) to
// a multiple of `step` (0 = continuous), so r − bias − zone bias has the density of a normal
// convolved with the uniform round-off: f(e) = [Φ((e + s/2)/σ) − Φ((e − s/2)/σ)]/s (s > 0), or
// N(0, σ²) (s = 0). The zone is a disc (centre, radius) in which readings carry an extra bias.
#include <vector>

#include "algorithms/diagnosis/odometry_channel.h"
#include "core/sensor_data.h"

namespace locbench::diagnosis {

struct CompassData {
  std::vector<CompassReading> readings;
  std::vector<TruePose> truth;
  double declared_step = 0.0;  // PARAM compass_resolution [rad], 0 when not declared
};

struct CompassZone {
  bool enabled = false;
  double x = 0.0, y = 0.0, radius = 0.0;  // [m]
  double bias = 0.0;                      // [rad]
  std::size_t candidates = 0;             // discs searched (for the scan's multiple-testing threshold)
};

struct CompassModel {
  double bias = 0.0;
  double step = 0.0;
  double sigma = 1e-3;
  double time_offset = 0.0;  // compass logged time − true time [s]
  CompassZone zone;
};

struct CompassResidual {
  double t = 0.0;
  double r = 0.0;           // reading − true heading (bias and zone not removed)
  double x = 0.0, y = 0.0;  // true position
  double turn_rate = 0.0;   // true [rad/s]
  bool valid = false;
};

std::vector<CompassResidual> compass_residuals(const CompassData& d, double time_offset);
double compass_nll(const CompassData& d, const CompassModel& m, const std::vector<std::size_t>& index);
// The disc with the largest likelihood gain for a constant extra bias inside it, searched over
// centres on the path and radii 0.25–4 m (at least 10 readings inside and 10 outside).
CompassZone best_compass_zone(const CompassData& d, const CompassModel& m, const std::vector<std::size_t>& index);

// The compass channel: the readings' lattice (quantization coarser than declared, found from
// the printed values), then forward selection of compass_bias, sensor_time_offset (profiled, as
// the odometry's) and compass_disturbance (the best disc, judged over all discs searched), with
// held-out gains in predictive likelihood. Needs COMPASS readings and TRUEPOS in `d`; returns an
// empty result (no tests, no causes) when fewer than 40 readings overlap the truth.
ChannelResult diagnose_compass(const MotionData& d, const DiagnosisOptions& options);

}  // namespace locbench::diagnosis
