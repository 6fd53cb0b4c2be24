// Classic (baselines/) and improved (algorithms/) UMBmark calibration on simulated UMBmark
// experiments with known truth: what they recover, with which uncertainty, and what re-running
// the square with the corrected nominal model does to E_max,syst.
//
// The "uncertainty we can justify" is twofold: (1) the closed forms are first-order, so even
// noise-free runs give a deterministic bias — the method applied to the noise-free square of
// predict_umbmark (checked against the simulator in umbmark_design_model_test); (2) floor noise
// and slip spread the estimates, by a Monte-Carlo standard deviation that the Fisher analysis
// (analyze_umbmark_design with the runs' pooled scatter) predicts. A Monte-Carlo mean over n seeds
// must lie within 3.5·sd/√n of the noise-free value.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "algorithms/calibration/umbmark_design_model.h"
#include "algorithms/calibration/umbmark_improved.h"
#include "baselines/calibration/umbmark_classic.h"
#include "core/statistics.h"
#include "core/units.h"
#include "datasets/sim/presets.h"
#include "datasets/sim/simulator.h"
#include "datasets/sim/umbmark_input.h"

namespace locbench::calibration {
using locbench::baselines::calibration::classic_umbmark, locbench::baselines::calibration::ClassicUmbmarkResult;
namespace {

sim::Scenario scenario(const char* name, bool slip) {
  sim::Scenario s = sim::preset(name);
  if (!slip) {
    s.slip.straight.rate = 0.0;
    s.slip.turn.rate = 0.0;
  }
  return s;
}

UmbmarkErrorParams truth_of(const sim::Scenario& s) { return error_params(s.robot.nominal, s.robot.actual); }

// The UMBmark input of a simulated experiment. No tape measurement: E_s = 1 (the runs were not
// E_s-compensated, see ClassicPutsAnUncompensatedTapeScaleOnTheTurns below).
UmbmarkInput experiment(const sim::Scenario& s, std::uint64_t seed) {
  return sim::umbmark_input(s, sim::simulate(s, seed).umbmark_runs, 1.0);
}

// The same experiment from the noise-free model: the methods' deterministic expectation.
UmbmarkInput noise_free(const sim::Scenario& s, const UmbmarkErrorParams& e) {
  const auto p = predict_umbmark(s.robot.nominal, s.robot.encoder, s.motion.side, e, {true, s.drive.equal_wheel_ticks});
  UmbmarkInput in = sim::umbmark_input(s, {}, 1.0);
  in.runs = {{UmbmarkDirection::kClockwise, p.cw.x(), p.cw.y()},
             {UmbmarkDirection::kCounterClockwise, p.ccw.x(), p.ccw.y()}};
  return in;
}

// E_max,syst of the square re-run with `corrected` as the robot's nominal model.
UmbmarkCentroids rerun(sim::Scenario s, const WheelGeometry& corrected, std::uint64_t seed) {
  s.robot.nominal = corrected;
  return umbmark_centroids(experiment(s, seed).runs);
}

struct MonteCarlo {
  std::vector<double> classic_E_d, classic_E_b, improved_E_d, improved_E_b, improved_E_o;
  std::vector<double> before, after_classic, after_improved;  // E_max,syst [m]
  std::vector<double> run_sigma;
};

MonteCarlo monte_carlo(const sim::Scenario& s, int seeds, bool rerun_square,
                       UmbmarkAngleFormula f = UmbmarkAngleFormula::kX) {
  MonteCarlo mc;
  for (int seed = 1; seed <= seeds; ++seed) {
    const UmbmarkInput in = experiment(s, static_cast<std::uint64_t>(seed));
    const auto c = classic_umbmark(in, {f});
    const auto i = improved_umbmark(in, {f, 0.0});
    mc.classic_E_d.push_back(c.E_d);
    mc.classic_E_b.push_back(c.E_b);
    mc.improved_E_d.push_back(i.E_d);
    mc.improved_E_b.push_back(i.E_b);
    mc.improved_E_o.push_back(i.E_o);
    mc.before.push_back(c.centroids.e_max_syst);
    mc.run_sigma.push_back(c.centroids.run_sigma);
    if (rerun_square) {  // an independent seed for the re-run
      mc.after_classic.push_back(rerun(s, c.corrected, 1000u + static_cast<std::uint64_t>(seed)).e_max_syst);
      mc.after_improved.push_back(rerun(s, i.corrected, 1000u + static_cast<std::uint64_t>(seed)).e_max_syst);
    }
  }
  return mc;
}

// |mean(v) − expected| ≤ 3.5·sd/√n + slack.
void expect_mean_near(const std::vector<double>& v, double expected, double slack, const char* what) {
  const double n = static_cast<double>(v.size());
  const double bound = 3.5 * sample_stddev(v) / std::sqrt(n) + slack;
  EXPECT_NEAR(mean(v), expected, bound) << what << ": Monte-Carlo mean " << mean(v) << " ± "
                                        << sample_stddev(v) / std::sqrt(n);
}

TEST(UmbmarkSimulated, NoiseFreeBorensteinSquareShowsTheClosedFormsFirstOrderBias) {
  // Truth E_d = 1.0025, E_b = 1.01, E_o = 1. From the exact noise-free return errors, 2.3a/2.6a
  // give E_d = 1.002367 (E_d − 1 5.3% low: β_x = 0.02782 vs the true 0.02908 rad per leg, and
  // 2.5 uses the nominal B) and E_b = 1.008939 (E_b − 1 10.6% low: α_x = 0.01392 vs 0.01555 rad,
  // the x formulas mix β into α at second order). The y formulas err the other way; their
  // mean (kMean) gives 1.002506 and 1.010297. The simulator reproduces these to 1e-6.
  sim::Scenario s = scenario("umbmark_borenstein", false);
  s.floor = {0.0, 0.0};
  const UmbmarkInput sim_in = experiment(s, 1);
  const UmbmarkInput model_in = noise_free(s, truth_of(s));
  const auto c = classic_umbmark(sim_in);
  EXPECT_NEAR(c.E_d, classic_umbmark(model_in).E_d, 1e-9);
  EXPECT_NEAR(c.E_b, classic_umbmark(model_in).E_b, 1e-9);
  EXPECT_NEAR(c.E_d, 1.002367, 1e-6);
  EXPECT_NEAR(c.E_b, 1.008939, 1e-6);
  const auto m = classic_umbmark(sim_in, {UmbmarkAngleFormula::kMean});
  EXPECT_NEAR(m.E_d, 1.002506, 1e-6);
  EXPECT_NEAR(m.E_b, 1.010297, 1e-6);
  // Improved: the same E_d; E_o = L/(N·c_n)(1 + β²/24) = 1.000032 whatever the truth, and
  // E_b = 1.008972 (Δα₂ = 90°(1 − E_o) = −5e-5 rad moved onto Δα₁).
  const auto i = improved_umbmark(sim_in);
  EXPECT_EQ(i.E_d, c.E_d);
  EXPECT_NEAR(i.E_o, 1.000032, 1e-6);
  EXPECT_NEAR(i.E_b, 1.008972, 1e-6);
}

TEST(UmbmarkSimulated, BorensteinMonteCarloRecoversEdAndEbWithinTheirStatedUncertainty) {
  // 10 seeds of the preset (floor noise k = 0.001 √m, no slip), 5 + 5 runs each.
  const sim::Scenario s = scenario("umbmark_borenstein", false);
  const UmbmarkErrorParams truth = truth_of(s);
  const MonteCarlo mc = monte_carlo(s, 10, true);
  const auto expected = classic_umbmark(noise_free(s, truth));
  const auto expected_improved = improved_umbmark(noise_free(s, truth));
  expect_mean_near(mc.classic_E_d, expected.E_d, 0.0, "classic E_d");
  expect_mean_near(mc.classic_E_b, expected.E_b, 0.0, "classic E_b");
  expect_mean_near(mc.improved_E_d, expected_improved.E_d, 0.0, "improved E_d");
  expect_mean_near(mc.improved_E_b, expected_improved.E_b, 0.0, "improved E_b");
  // …and so the truth, up to the first-order bias (≤ 6% of E_d − 1, ≤ 11% of E_b − 1).
  expect_mean_near(mc.classic_E_d, truth.E_d, 0.06 * (truth.E_d - 1.0), "classic E_d vs truth");
  expect_mean_near(mc.classic_E_b, truth.E_b, 0.11 * (truth.E_b - 1.0), "classic E_b vs truth");

  // The spread of one experiment's estimate is what the Fisher information predicts from the
  // runs' own scatter (≈ 45 mm per run here): se(E_d) ≈ 1.1e-4, se(E_b) ≈ 8e-4.
  UmbmarkIdentifiabilityOptions o;
  o.run_sigma = mean(mc.run_sigma);
  o.model = {true, false};
  const auto f = analyze_umbmark_design(UmbmarkDesign::kSquare, UmbmarkParameterSet::kClassic, s.robot.nominal,
                                        s.robot.encoder, s.motion.side, truth, o);
  for (const auto& [v, se] : {std::pair{&mc.classic_E_d, f.report.parameters[0].standard_error},
                              std::pair{&mc.classic_E_b, f.report.parameters[1].standard_error}}) {
    EXPECT_GT(sample_stddev(*v), 0.5 * se);
    EXPECT_LT(sample_stddev(*v), 2.0 * se);
  }

  // Re-running the square with the corrected nominal model: E_max,syst ≈ 0.5 m → a few cm,
  // Borenstein's "at least 10×" (the x formulas' bias leaves ~10% of E_b − 1 uncorrected).
  EXPECT_GT(mean(mc.before), 0.4);
  EXPECT_LT(mean(mc.after_classic), mean(mc.before) / 5.0);
  EXPECT_LT(mean(mc.after_improved), mean(mc.before) / 5.0);
}

TEST(UmbmarkSimulated, BorensteinWithTurnSlipPutsTheMeanSlipLossOnEb) {
  // Turn slip (20% of samples, 5–15% of one wheel's travel) shortens every turn on average, so
  // the Type A angle and E_b grow. The simulator logs every slip event: the mean turn shortfall
  // δ = Σ|lost|/B/(8·runs) makes an effective E_b' = E_b·τ/(τ − δ), and the estimates must match
  // the method applied to the noise-free square with E_b' (per seed, then averaged).
  sim::Scenario s = scenario("umbmark_borenstein", true);
  s.slip.turn = {0.2, 0.05, 0.15};
  const UmbmarkErrorParams truth = truth_of(s);
  const double tau = predict_umbmark(s.robot.nominal, s.robot.encoder, s.motion.side, truth).turn_angle;
  std::vector<double> residual_E_b, residual_E_d, before, after, eff;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    const auto r = sim::simulate(s, seed);
    double lost = 0.0;
    for (const auto& e : r.slips) {
      if (e.phase == sim::MotionPhase::kTurn) lost += std::abs(e.lost);
    }
    UmbmarkErrorParams effective = truth;
    effective.E_b = truth.E_b * tau / (tau - lost / s.robot.actual.wheelbase / (8.0 * s.motion.runs));
    eff.push_back(effective.E_b);
    const auto c = classic_umbmark(sim::umbmark_input(s, r.umbmark_runs, 1.0));
    const auto expected = classic_umbmark(noise_free(s, effective));
    residual_E_b.push_back(c.E_b - expected.E_b);
    residual_E_d.push_back(c.E_d - expected.E_d);
    before.push_back(c.centroids.e_max_syst);
    after.push_back(rerun(s, c.corrected, 1000 + seed).e_max_syst);
  }
  EXPECT_GT(mean(eff), truth.E_b + 0.005);  // ≈ 0.8° of slip per turn
  expect_mean_near(residual_E_b, 0.0, 2e-4, "E_b − expectation with the slip-effective E_b");
  expect_mean_near(residual_E_d, 0.0, 0.0, "E_d − expectation");
  // The mean slip is compensated like a wheelbase error; what remains is its randomness.
  EXPECT_LT(mean(after), mean(before) / 3.0);
}

TEST(UmbmarkSimulated, TrilobotWithoutSlipRecoversEdAndHalvesEMaxSyst) {
  // Trilobot, 1.6 m square, floor noise k = 0.005 √m (≈2.6° of heading noise per leg), 12.7 mm
  // ticks. Truth E_d = 1.004842; the quantised noise-free expectation with kMean is 1.005037.
  // E_b is only seen through E_o/E_b = 1.00639 (12 tick turns of 88.33° against the odometry's
  // 87.77°): classic E_b ≈ 0.994 (kMean, noise-free).
  const sim::Scenario s = scenario("umbmark_trilobot", false);
  const UmbmarkErrorParams truth = truth_of(s);
  const MonteCarlo mc = monte_carlo(s, 10, true, UmbmarkAngleFormula::kMean);
  const auto expected = classic_umbmark(noise_free(s, truth), {UmbmarkAngleFormula::kMean});
  expect_mean_near(mc.classic_E_d, expected.E_d, 0.0, "classic E_d");
  expect_mean_near(mc.classic_E_d, truth.E_d, 3e-4, "classic E_d vs truth");
  expect_mean_near(mc.classic_E_b, expected.E_b, 0.0, "classic E_b");
  expect_mean_near(mc.classic_E_b, truth.E_b / truth.E_o, 0.002, "classic E_b vs E_b/E_o");
  EXPECT_LT(mean(mc.after_classic), mean(mc.before) / 1.5);
  EXPECT_LT(mean(mc.after_improved), mean(mc.before) / 1.5);
}

TEST(UmbmarkSimulated, TrilobotWithTurnSlipLikeTheThesis) {
  // The preset as the thesis ran it: heavy slip in on-the-spot turns. E_max,syst before is
  // 0.45–0.75 m (Table 2.1: 650–773 mm); the turn slip (≈5° per turn) appears as E_b ≈ 1.04;
  // re-running with either correction cuts E_max,syst by 2–3× (Table 2.1: 3.5–5.7×). The
  // improved method's E_o is 1.6/(127·12.638 mm) = 0.99689 on every seed — the rounding of the
  // commanded leg — while the true E_o is 1.00604.
  const sim::Scenario s = scenario("umbmark_trilobot", true);
  const UmbmarkErrorParams truth = truth_of(s);
  const MonteCarlo mc = monte_carlo(s, 10, true, UmbmarkAngleFormula::kMean);
  EXPECT_GT(mean(mc.before), 0.45);
  EXPECT_LT(mean(mc.before), 0.75);
  EXPECT_GT(mean(mc.classic_E_b), truth.E_b + 0.02);
  expect_mean_near(mc.classic_E_d, truth.E_d, 3e-4, "classic E_d vs truth (kMean)");
  const double c_n = kPi * mm(88.5) / 22.0;
  for (const double e_o : mc.improved_E_o) EXPECT_NEAR(e_o, 1.6 / (127 * c_n), 2e-4);
  EXPECT_NEAR(1.6 / (127 * c_n), 0.99689, 1e-5);
  EXPECT_LT(mean(mc.after_classic), mean(mc.before) / 2.0);
  EXPECT_LT(mean(mc.after_improved), mean(mc.before) / 2.0);
}

// The Type B angle β and Type A angle α of a set of centroids (kMean of 2.3a/b and 2.6a/b).
std::pair<double, double> angles(const UmbmarkCentroids& c, double side) {
  const double k = -4.0 * side;
  return {0.5 * ((c.cw.x() - c.ccw.x()) + (c.cw.y() + c.ccw.y())) / k,
          0.5 * ((c.cw.x() + c.ccw.x()) + (c.cw.y() - c.ccw.y())) / k};
}

// Where the robot really ended, true end − start in the start frame: the closure of the driven
// path, as opposed to the odometry's return error ε = true end − odometry end.
UmbmarkCentroids path_closure(const std::vector<sim::UmbmarkRun>& runs) {
  std::vector<UmbmarkReturn> out;
  for (const auto& r : runs) {
    const Pose2 d = between(r.start, r.true_end);
    out.push_back(
        {r.direction == sim::Direction::kClockwise ? UmbmarkDirection::kClockwise : UmbmarkDirection::kCounterClockwise,
         d.x, d.y});
  }
  return umbmark_centroids(out);
}

struct TypeAB {
  std::vector<double> beta, alpha;
  void add(const UmbmarkCentroids& c, double side) {
    const auto [b, a] = angles(c, side);
    beta.push_back(b);
    alpha.push_back(a);
  }
};

// Classic UMBmark (mean angle formula) on run `seed` of `s`, its return errors added to
// `before`; then the runs again (seed 1000 + seed) with its one conversion factor
// {D_a, D_a, B_actual}, added to `after`. Returns the calibration.
ClassicUmbmarkResult calibrate_with_one_factor(const sim::Scenario& s, std::uint64_t seed, TypeAB& before,
                                               TypeAB& after) {
  const auto c = classic_umbmark(experiment(s, seed), {UmbmarkAngleFormula::kMean});
  before.add(c.centroids, s.motion.side);
  sim::Scenario a = s;
  a.robot.nominal = {c.D_a, c.D_a, c.B_actual};
  after.add(umbmark_centroids(experiment(a, 1000 + seed).runs), s.motion.side);
  return c;
}

TEST(UmbmarkSimulated, WithEqualWheelTicksOnlyTypeACanBeCompensated) {
  // drive.equal_wheel_ticks (the Trilobot's limitation, §2.4): both wheels always get the same
  // count, so the calibrated unequal diameters cannot be commanded. Borenstein's fine-tick robot
  // (β ≈ 1.68°, α ≈ 0.92° before; 4 seeds) shows the three cases:
  //  * a robot whose software takes one conversion factor only gets {D_a, D_a, B_actual}: α goes,
  //    β stays in the return errors — only Type A is compensated;
  //  * with per-wheel factors in its odometry the return errors lose β too (the odometry now
  //    knows the legs curve), but the driven path still curves: its closure keeps β;
  //  * with independent wheels the path is straightened as well.
  sim::Scenario s = scenario("umbmark_borenstein", false);
  s.drive.equal_wheel_ticks = true;
  sim::Scenario independent = s;
  independent.drive.equal_wheel_ticks = false;
  TypeAB before, one_factor, odometry, path, independent_path;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const auto c = calibrate_with_one_factor(s, seed, before, one_factor);
    sim::Scenario full = s;
    full.robot.nominal = c.corrected;
    const auto runs = sim::simulate(full, 1000 + seed).umbmark_runs;
    odometry.add(umbmark_centroids(sim::umbmark_returns(runs)), s.motion.side);
    path.add(path_closure(runs), s.motion.side);
    independent.robot.nominal = c.corrected;
    independent_path.add(path_closure(sim::simulate(independent, 1000 + seed).umbmark_runs), s.motion.side);
  }
  const double beta0 = mean(before.beta), alpha0 = mean(before.alpha);
  EXPECT_NEAR(beta0, deg(1.68), deg(0.2));
  EXPECT_NEAR(alpha0, deg(0.92), deg(0.3));
  EXPECT_NEAR(mean(one_factor.beta), beta0, 0.1 * beta0);
  EXPECT_LT(std::abs(mean(one_factor.alpha)), 0.2 * alpha0);
  EXPECT_LT(std::abs(mean(odometry.beta)), 0.1 * beta0);
  EXPECT_LT(std::abs(mean(odometry.alpha)), 0.2 * alpha0);
  EXPECT_NEAR(mean(path.beta), beta0, 0.1 * beta0);
  EXPECT_LT(std::abs(mean(independent_path.beta)), 0.1 * beta0);
}

TEST(UmbmarkSimulated, TrilobotWithEqualWheelTicksKeepsItsTypeBError) {
  // The same on the Trilobot (slip off, 8 seeds) with one conversion factor for both wheels:
  // β ≈ 2.3° per leg before and after, within the Monte-Carlo spread.
  sim::Scenario s = scenario("umbmark_trilobot", false);
  s.drive.equal_wheel_ticks = true;
  TypeAB before, after;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    calibrate_with_one_factor(s, seed, before, after);
  }
  EXPECT_GT(mean(before.beta), deg(1.5));
  const double n = static_cast<double>(before.beta.size());
  EXPECT_NEAR(mean(after.beta), mean(before.beta),
              3.5 * std::hypot(sample_stddev(after.beta), sample_stddev(before.beta)) / std::sqrt(n));
}

TEST(UmbmarkSimulated, ClassicPutsAnUncompensatedTapeScaleOnTheTurns) {
  // Borenstein measures E_s with a tape and compensates it in software *before* the runs. If
  // the runs are driven uncompensated (E_o = 0.99 here, E_d = E_b = 1), α = 90°(1 − E_o/E_b)
  // makes E_b = 1/0.99 ≈ 1.0101 — the thesis's point that E_s's turn error lands in E_b. Using
  // the tape's E_s = 0.99 as well then shrinks the tick size and the turns become 90°/0.99 =
  // 90.91° (wrong by 0.91°); leaving E_s = 1 gives 90° (the legs are 1% short, which a closed
  // square does not see). The improved method's E_o ≈ 1 behaves like E_s = 1.
  const WheelGeometry nominal{0.15, 0.15, 0.34};
  const EncoderSpec encoder{43.8, 2048.0};
  const UmbmarkErrorParams truth{1.0, 1.0, 0.99};
  const WheelGeometry actual = true_geometry(nominal, truth);
  const auto p = predict_umbmark(nominal, encoder, 4.0, truth, {false, false});
  UmbmarkInput in;
  in.side_length = 4.0;
  in.nominal = nominal;
  in.encoder = encoder;
  in.leg_ticks_left = in.leg_ticks_right = std::llround(4.0 / (kPi * 0.15 / (43.8 * 2048.0)));
  in.runs = {{UmbmarkDirection::kClockwise, p.cw.x(), p.cw.y()},
             {UmbmarkDirection::kCounterClockwise, p.ccw.x(), p.ccw.y()}};
  auto turn_after = [&](const WheelGeometry& corrected) {
    return to_deg(predict_umbmark(corrected, encoder, 4.0, error_params(corrected, actual), {false, false}).turn_angle);
  };
  in.tape_measure_scale = 0.99;
  const auto with_tape = classic_umbmark(in, {UmbmarkAngleFormula::kMean});
  EXPECT_NEAR(with_tape.E_b, 1.0 / 0.99, 3e-4);
  EXPECT_NEAR(turn_after(with_tape.corrected), 90.0 / 0.99, 0.03);
  in.tape_measure_scale = 1.0;
  EXPECT_NEAR(turn_after(classic_umbmark(in, {UmbmarkAngleFormula::kMean}).corrected), 90.0, 0.03);
  EXPECT_NEAR(turn_after(improved_umbmark(in, {UmbmarkAngleFormula::kMean, 0.0}).corrected), 90.0, 0.03);
}

}  // namespace
}  // namespace locbench::calibration
