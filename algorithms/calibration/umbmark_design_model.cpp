#include "algorithms/calibration/umbmark_design_model.h"

#include <fmt/format.h>
#include <cmath>
#include <stdexcept>

#include "core/diff_drive_odometry.h"
#include "core/pose2.h"
#include "core/units.h"

namespace locbench::calibration {

WheelGeometry true_geometry(const WheelGeometry& nominal, const UmbmarkErrorParams& e) {
  const double d_a = e.E_o * nominal.mean_diameter();  // 2.16
  const double d_l = 2.0 * d_a / (e.E_d + 1.0);        // 2.9 with 2.1: D_L + E_d·D_L = 2·D_a
  return {d_l, e.E_d * d_l, e.E_b * nominal.wheelbase};
}

UmbmarkErrorParams error_params(const WheelGeometry& nominal, const WheelGeometry& actual) {
  return {actual.diameter_right / actual.diameter_left, actual.wheelbase / nominal.wheelbase,
          actual.mean_diameter() / nominal.mean_diameter()};
}

namespace {

// Exact motion along the circular arc that wheel travels (left, right) describe.
Pose2 arc(const Pose2& p, double left, double right, double wheelbase) {
  return exact_arc_step(p, {left, right}, wheelbase);
}

struct Ticks {
  double left = 0.0;
  double right = 0.0;
};

// Counts for wheel travels (left, right) under the nominal model (motion_program.cpp).
Ticks command(double left, double right, const NominalModel& m, const UmbmarkDesignOptions& o) {
  auto count = [&](double travel, double c) {
    return o.quantize_counts ? static_cast<double>(std::llround(travel / c)) : travel / c;
  };
  if (o.equal_wheel_ticks) {
    const double c = 0.5 * (m.meters_per_tick_left + m.meters_per_tick_right);
    return {std::copysign(count(std::abs(left), c), left), std::copysign(count(std::abs(right), c), right)};
  }
  return {std::copysign(count(std::abs(left), m.meters_per_tick_left), left),
          std::copysign(count(std::abs(right), m.meters_per_tick_right), right)};
}

}  // namespace

UmbmarkPrediction predict_umbmark(const WheelGeometry& nominal, const EncoderSpec& encoder, double side_length,
                                  const UmbmarkErrorParams& truth, const UmbmarkDesignOptions& options) {
  const RobotParams robot{nominal, true_geometry(nominal, truth), encoder};
  const NominalModel nm = robot.nominal_model();
  const NominalModel am = robot.actual_model();
  const double quarter_arc = 0.25 * kPi * nominal.wheelbase;  // (π/2)·B/2
  const Ticks leg = command(side_length, side_length, nm, options);
  const Ticks turn = command(quarter_arc, quarter_arc, nm, options);

  UmbmarkPrediction out;
  out.leg_ticks_left = leg.left;
  out.leg_ticks_right = leg.right;
  out.turn_ticks_left = turn.left;
  out.turn_ticks_right = turn.right;
  const double true_left = leg.left * am.meters_per_tick_left;
  const double true_right = leg.right * am.meters_per_tick_right;
  const Pose2 one_leg = arc(Pose2{}, true_left, true_right, am.wheelbase);
  out.leg_chord = std::hypot(one_leg.x, one_leg.y);
  out.leg_heading_change = (true_right - true_left) / am.wheelbase;
  out.turn_angle = (turn.left * am.meters_per_tick_left + turn.right * am.meters_per_tick_right) / am.wheelbase;

  for (const bool cw : {true, false}) {
    const double sign = cw ? -1.0 : 1.0;  // clockwise: right turns
    Pose2 t, o;                           // true pose and odometry, start frame
    for (int side = 0; side < 4; ++side) {
      t = arc(t, true_left, true_right, am.wheelbase);
      o = arc(o, leg.left * nm.meters_per_tick_left, leg.right * nm.meters_per_tick_right, nm.wheelbase);
      t = arc(t, -sign * turn.left * am.meters_per_tick_left, sign * turn.right * am.meters_per_tick_right,
              am.wheelbase);
      o = arc(o, -sign * turn.left * nm.meters_per_tick_left, sign * turn.right * nm.meters_per_tick_right,
              nm.wheelbase);
    }
    const Eigen::Vector2d e = t.translation() - o.translation();
    const double h = angle_diff(t.theta, o.theta);
    (cw ? out.cw : out.ccw) = e;
    (cw ? out.heading_cw : out.heading_ccw) = h;
  }
  return out;
}

std::string to_string(UmbmarkDesign d) {
  switch (d) {
    case UmbmarkDesign::kSquare: return "square";
    case UmbmarkDesign::kSquareWithLegTicks: return "square + logged leg counts N_L, N_R";
    case UmbmarkDesign::kSquareWithTapedLeg: return "square + tape-measured straight leg";
    case UmbmarkDesign::kSquareWithTapedLegAndLegTicks:
      return "square + tape-measured straight leg + logged leg counts";
  }
  return "?";
}

std::string to_string(UmbmarkParameterSet p) {
  return p == UmbmarkParameterSet::kClassic ? "classic (E_d, E_b; E_o known)" : "improved (E_d, E_b, E_o)";
}

namespace {

bool has_leg_ticks(UmbmarkDesign d) {
  return d == UmbmarkDesign::kSquareWithLegTicks || d == UmbmarkDesign::kSquareWithTapedLegAndLegTicks;
}
bool has_taped_leg(UmbmarkDesign d) {
  return d == UmbmarkDesign::kSquareWithTapedLeg || d == UmbmarkDesign::kSquareWithTapedLegAndLegTicks;
}

// The design's measurement vector: centroids (x_cw, y_cw, x_ccw, y_ccw) [m], then N_L, N_R
// [ticks] and/or the taped leg length [m].
Eigen::VectorXd measure(UmbmarkDesign design, const UmbmarkPrediction& p) {
  std::vector<double> m{p.cw.x(), p.cw.y(), p.ccw.x(), p.ccw.y()};
  if (has_leg_ticks(design)) {
    m.push_back(p.leg_ticks_left);
    m.push_back(p.leg_ticks_right);
  }
  if (has_taped_leg(design)) m.push_back(p.leg_chord);
  return Eigen::Map<const Eigen::VectorXd>(m.data(), static_cast<Eigen::Index>(m.size()));
}

std::string remedy_for(const std::string& parameter) {
  if (parameter == "E_o") {
    return "measure the true length of one straight leg with a tape (its counts × nominal metres "
           "per tick over the taped length is 1/E_o); the return errors alone only see the turn "
           "angle, which depends on E_o/E_b";
  }
  if (parameter == "E_b") {
    return "fix E_o independently — measure the true length of one straight leg with a tape; "
           "the Type A angle then gives E_b through E_o/E_b";
  }
  return "measure the heading change of one straight leg (e.g. a long straight run against a "
         "taped line): it is the Type B angle β that E_d follows from";
}

}  // namespace

UmbmarkDesignFinding analyze_umbmark_design(UmbmarkDesign design, UmbmarkParameterSet set, const WheelGeometry& nominal,
                                            const EncoderSpec& encoder, double side_length,
                                            const UmbmarkErrorParams& at,
                                            const UmbmarkIdentifiabilityOptions& options) {
  if (options.run_sigma <= 0.0 || options.runs_per_direction < 1 || options.tape_sigma <= 0.0 ||
      options.tick_sigma <= 0.0 || options.relative_step <= 0.0) {
    throw std::invalid_argument("analyze_umbmark_design: sigmas, runs and step must be > 0");
  }
  UmbmarkDesignFinding f;
  f.design = design;
  f.parameter_set = set;
  std::vector<std::string> names{"E_d", "E_b"};
  if (set == UmbmarkParameterSet::kImproved) names.push_back("E_o");
  const Eigen::Index p = static_cast<Eigen::Index>(names.size());
  Eigen::VectorXd values(p);
  values(0) = at.E_d;
  values(1) = at.E_b;
  if (p == 3) values(2) = at.E_o;

  auto params_of = [&](const Eigen::VectorXd& v) {
    UmbmarkErrorParams e = at;
    e.E_d = v(0);
    e.E_b = v(1);
    if (p == 3) e.E_o = v(2);
    return e;
  };
  auto h = [&](const Eigen::VectorXd& v) {
    return measure(design, predict_umbmark(nominal, encoder, side_length, params_of(v), options.model));
  };
  const Eigen::VectorXd y0 = h(values);
  f.jacobian = Eigen::MatrixXd::Zero(y0.size(), p);
  for (Eigen::Index j = 0; j < p; ++j) {  // central differences
    const double step = options.relative_step * std::max(1.0, std::abs(values(j)));
    Eigen::VectorXd plus = values, minus = values;
    plus(j) += step;
    minus(j) -= step;
    f.jacobian.col(j) = (h(plus) - h(minus)) / (2.0 * step);
  }

  f.measurements = {"x_cg,cw", "y_cg,cw", "x_cg,ccw", "y_cg,ccw"};
  std::vector<double> variances(
      4, options.run_sigma * options.run_sigma / static_cast<double>(options.runs_per_direction));
  if (has_leg_ticks(design)) {
    f.measurements.insert(f.measurements.end(), {"N_L", "N_R"});
    variances.insert(variances.end(), 2, options.tick_sigma * options.tick_sigma);
  }
  if (has_taped_leg(design)) {
    f.measurements.push_back("taped leg length");
    variances.push_back(options.tape_sigma * options.tape_sigma);
  }
  const Eigen::VectorXd var =
      Eigen::Map<const Eigen::VectorXd>(variances.data(), static_cast<Eigen::Index>(variances.size()));
  f.report = analyze_identifiability(f.jacobian, var.asDiagonal().toDenseMatrix(), names, values);

  for (auto& par : f.report.parameters) {
    if (par.identifiable && par.standard_error > options.max_standard_error) {
      par.identifiable = false;
      par.reason = fmt::format(
          "formally determined (Fisher rank {}) but only with standard error {:.3g} > {:.3g}: "
          "the information comes from second-order effects of the square",
          f.report.rank, par.standard_error, options.max_standard_error);
    }
    if (!par.identifiable) f.remedies.emplace_back(par.name, remedy_for(par.name));
  }
  return f;
}

}  // namespace locbench::calibration
