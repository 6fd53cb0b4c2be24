#pragma once
// Shared by the slip/* experiments (chapter 3): turns a simulated run into the per-sample
// inputs of the slip detector and the filters, adds a simulated gyro, fits the slip model
// (μ, σ of Δθ') from calibration runs, and scores detections against the simulator's true slip
// events. Header-only, internal to the experiments.
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <vector>

#include "algorithms/slip/indirect_kalman_filter.h"
#include "algorithms/slip/slip_compass_ekf.h"
#include "core/angle.h"
#include "core/diff_drive_odometry.h"
#include "core/rng.h"
#include "datasets/sim/simulation_result.h"
#include "datasets/sim/simulator.h"

namespace locbench::experiments::slip_sim {

// A simple rate gyro (ours; the simulator has none): per encoder sample of length dt,
// θ_G = true heading increment + bias·dt + N(0, (noise_density)²·dt).
struct GyroConfig {
  double bias = deg(0.05);          // [rad/s]
  double noise_density = deg(0.1);  // [rad/√s]
};

struct RunData {
  std::vector<slip::SlipSample> samples;  // one per encoder interval k−1 → k (k ≥ 1)
  std::optional<double> initial_compass;  // reading nearest the first encoder sample
  std::vector<Pose2> truth;               // true pose at each encoder sample (size = samples + 1)
  double wheelbase = 0.0;                 // of the model used for the wheel travel
};

inline std::optional<double> nearest_compass(const Log& log, double t, double max_offset) {
  const auto& c = log.compass;
  const auto it = std::lower_bound(c.begin(), c.end(), t, [](const CompassReading& r, double v) { return r.t < v; });
  std::optional<double> best;
  double best_dt = max_offset;
  if (it != c.end() && std::abs(it->t - t) <= best_dt) {
    best = it->heading;
    best_dt = std::abs(it->t - t);
  }
  if (it != c.begin() && std::abs(std::prev(it)->t - t) <= best_dt) best = std::prev(it)->heading;
  return best;
}

// Wheel travel with `model` (the robot's belief), compass readings nearest each encoder sample
// (within half a period), and, if `gyro` is set, a gyro increment drawn from `rng`.
inline RunData run_data(const sim::SimulationResult& r, const NominalModel& model,
                        const std::optional<GyroConfig>& gyro, Rng* rng) {
  const auto& enc = r.log.encoders;
  if (enc.size() < 2 || r.wheel_samples.size() != enc.size()) {
    throw std::logic_error("slip experiment: run without encoder samples");
  }
  const double half_period = 0.5 / r.scenario.encoders.timing.rate;
  RunData d;
  d.wheelbase = model.wheelbase;
  d.initial_compass = nearest_compass(r.log, enc.front().t, half_period);
  d.truth.push_back(r.wheel_samples.front().pose);
  for (std::size_t k = 1; k < enc.size(); ++k) {
    slip::SlipSample s;
    s.u = displacement_from_ticks(model, enc[k].left - enc[k - 1].left, enc[k].right - enc[k - 1].right);
    s.compass = nearest_compass(r.log, enc[k].t, half_period);
    const auto& w0 = r.wheel_samples[k - 1];
    const auto& w1 = r.wheel_samples[k];
    if (gyro && rng) {
      const double dt = w1.t - w0.t;
      s.gyro_increment = angle_diff(w1.pose.theta, w0.pose.theta) + gyro->bias * dt +
                         rng->normal(0.0, gyro->noise_density * std::sqrt(std::max(dt, 0.0)));
    }
    d.samples.push_back(s);
    d.truth.push_back(w1.pose);
  }
  return d;
}

// What the filters need of a run under any model (the model only turns ticks into wheel travel):
// each interval's tick increments and the compass reading nearest its end, and the true pose at
// each encoder sample. A Monte-Carlo record that carries it lets a second pass re-run the
// filters under models known only once every run is done, without simulating the run again.
struct RunTicks {
  std::vector<std::array<std::int64_t, 2>> ticks;  // (ΔN_L, ΔN_R) of interval k−1 → k
  std::vector<std::optional<double>> compass;      // nearest the end of each interval
  std::optional<double> initial_compass;           // nearest the first encoder sample
  std::vector<Pose2> truth;                        // at each encoder sample (size = ticks + 1)
};

inline RunTicks run_ticks(const sim::SimulationResult& r) {
  const auto& enc = r.log.encoders;
  if (enc.size() < 2 || r.wheel_samples.size() != enc.size()) {
    throw std::logic_error("slip experiment: run without encoder samples");
  }
  const double half_period = 0.5 / r.scenario.encoders.timing.rate;
  RunTicks t;
  t.initial_compass = nearest_compass(r.log, enc.front().t, half_period);
  t.truth.push_back(r.wheel_samples.front().pose);
  for (std::size_t k = 1; k < enc.size(); ++k) {
    t.ticks.push_back({enc[k].left - enc[k - 1].left, enc[k].right - enc[k - 1].right});
    t.compass.push_back(nearest_compass(r.log, enc[k].t, half_period));
    t.truth.push_back(r.wheel_samples[k].pose);
  }
  return t;
}

// As run_data(r, model, {}, nullptr) of the run the ticks were taken from.
inline RunData run_data(const RunTicks& t, const NominalModel& model) {
  RunData d;
  d.wheelbase = model.wheelbase;
  d.initial_compass = t.initial_compass;
  d.truth = t.truth;
  for (std::size_t k = 0; k < t.ticks.size(); ++k) {
    slip::SlipSample s;
    s.u = displacement_from_ticks(model, t.ticks[k][0], t.ticks[k][1]);
    s.compass = t.compass[k];
    d.samples.push_back(s);
  }
  return d;
}

// As JSON: {"ticks": [[ΔN_L, ΔN_R], …], "compass": [rad or null, …], "initial_compass": rad or
// null, "truth": [[x, y, θ], …]}; doubles read back exactly.
inline nlohmann::json run_ticks_json(const RunTicks& t) {
  auto optional = [](const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); };
  nlohmann::json j = {{"ticks", t.ticks}, {"compass", nlohmann::json::array()}, {"truth", nlohmann::json::array()}};
  for (const auto& c : t.compass) j["compass"].push_back(optional(c));
  j["initial_compass"] = optional(t.initial_compass);
  for (const Pose2& p : t.truth) j["truth"].push_back({p.x, p.y, p.theta});
  return j;
}

inline RunTicks run_ticks_from_json(const nlohmann::json& j) {
  auto optional = [](const nlohmann::json& v) {
    return v.is_null() ? std::optional<double>() : std::optional<double>(v.get<double>());
  };
  RunTicks t;
  t.ticks = j.at("ticks").get<std::vector<std::array<std::int64_t, 2>>>();
  for (const auto& c : j.at("compass")) t.compass.push_back(optional(c));
  t.initial_compass = optional(j.at("initial_compass"));
  for (const auto& p : j.at("truth"))
    t.truth.push_back({p.at(0).get<double>(), p.at(1).get<double>(), p.at(2).get<double>()});
  if (t.compass.size() != t.ticks.size() || t.truth.size() != t.ticks.size() + 1) {
    throw std::invalid_argument("slip experiment: a record's run ticks, compass readings and truth disagree in length");
  }
  return t;
}

// The simulations the slip experiments have made in this process (tests: one per run).
inline std::atomic<std::size_t> simulations{0};
inline sim::SimulationResult simulate(const sim::Scenario& scenario, std::uint64_t seed) {
  ++simulations;
  return sim::simulate(scenario, seed);
}

// The run as the indirect Kalman filter takes it: each sample's wheel travel with its compass
// reading, and the end-position error of the odometry dead-reckoned from the true start
// (true end − odometry end), the IKF's end-position measurement.
struct IkfRun {
  std::vector<slip::IkfSample> samples;
  Eigen::Vector2d end_error = Eigen::Vector2d::Zero();
};
inline IkfRun ikf_run(const RunData& d) {
  IkfRun out;
  Pose2 odo = d.truth.front();
  for (const slip::SlipSample& x : d.samples) {
    out.samples.push_back({x.u, x.compass});
    odo = odometry_step(odo, x.u, d.wheelbase);
  }
  out.end_error = Eigen::Vector2d(d.truth.back().x - odo.x, d.truth.back().y - odo.y);
  return out;
}

// Δθ' = θ_E − θ_ref of the samples where the robot moved and a reference increment exists;
// `use_gyro` takes the gyro increments instead of the compass's. With `check_disturbance`,
// samples failing rule 3 are left out.
inline void collect_delta_prime(const RunData& d, bool use_gyro, std::vector<double>& out) {
  std::optional<double> prev = d.initial_compass;
  for (const slip::SlipSample& s : d.samples) {
    const double theta_e = (s.u.right - s.u.left) / d.wheelbase;
    std::optional<double> ref;
    if (use_gyro) {
      ref = s.gyro_increment;
    } else if (s.compass && prev) {
      ref = angle_diff(*s.compass, *prev);
    }
    if (s.compass) prev = s.compass;
    if (!ref || (s.u.left == 0.0 && s.u.right == 0.0)) continue;
    if (!use_gyro && slip::compass_disturbed(s.u, *ref, d.wheelbase)) continue;
    out.push_back(theta_e - *ref);
  }
}

// Detection scoring. A detection at sample j (encoder interval j → j+1) is a true positive when
// the simulator has a slip event with `sample == j` on the same wheel; a detection at an event's
// interval naming the other wheel counts as a false positive and as "wrong wheel".
struct DetectionScore {
  std::size_t true_events = 0;  // events on intervals where the robot moved
  std::size_t detections = 0;
  std::size_t true_positives = 0;
  std::size_t wrong_wheel = 0;
  std::size_t large_events = 0;  // events losing ≥ `large` metres
  std::size_t large_detected = 0;
};
inline DetectionScore score_detections(const slip::SlipEkfRun& run, const sim::SimulationResult& r, double large) {
  DetectionScore s;
  for (const auto& e : r.slips) {
    if (e.sample >= run.steps.size() || e.lost == 0.0) continue;
    ++s.true_events;
    const bool is_large = std::abs(e.lost) >= large;
    if (is_large) ++s.large_events;
    const slip::SampleStatus want =
        e.wheel == sim::Side::kLeft ? slip::SampleStatus::kLeftSlip : slip::SampleStatus::kRightSlip;
    const slip::SampleStatus got = run.steps[e.sample].decision.status;
    if (got == want) {
      ++s.true_positives;
      if (is_large) ++s.large_detected;
    } else if (run.steps[e.sample].decision.slipped()) {
      ++s.wrong_wheel;
    }
  }
  for (const auto& st : run.steps) s.detections += st.decision.slipped() ? 1 : 0;
  return s;
}

// μ, σ of θ_E − θ_C (and of θ_E − θ_G when `gyro` is set) from `runs` calibration runs of the
// scenario with seeds Rng::derive_seed(seed, kCalibrationSeedBase + i); the thesis used 4 runs.
inline constexpr std::uint64_t kCalibrationSeedBase = 100000;
inline constexpr std::uint64_t kGyroStream = 77;  // Rng::stream(run seed, ·) of the gyro
struct CalibratedModels {
  slip::SlipModel compass;
  std::optional<slip::SlipModel> gyro;
  std::size_t samples = 0;
};
inline CalibratedModels calibrate(const sim::Scenario& scenario, std::uint64_t seed, int runs,
                                  const std::optional<GyroConfig>& gyro) {
  std::vector<double> dp_compass, dp_gyro;
  for (int i = 0; i < runs; ++i) {
    const std::uint64_t s = Rng::derive_seed(seed, kCalibrationSeedBase + static_cast<std::uint64_t>(i));
    const sim::SimulationResult r = slip_sim::simulate(scenario, s);
    Rng g = Rng::stream(s, kGyroStream);
    const RunData d = run_data(r, *r.log.nominal_model(), gyro, &g);
    collect_delta_prime(d, false, dp_compass);
    if (gyro) collect_delta_prime(d, true, dp_gyro);
  }
  CalibratedModels m;
  m.compass = slip::fit_slip_model(dp_compass);
  if (gyro) m.gyro = slip::fit_slip_model(dp_gyro);
  m.samples = dp_compass.size();
  return m;
}

inline double final_position_error(const slip::SlipEkfRun& run, const RunData& d) {
  const Pose2& t = d.truth.back();
  return std::hypot(run.final_pose.x - t.x, run.final_pose.y - t.y);
}

}  // namespace locbench::experiments::slip_sim
