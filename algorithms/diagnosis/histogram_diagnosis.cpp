// Diagnosis of a histogram of residuals (bin edges and counts), e.g. the thesis's Table 3.1 of
// encoder-minus-compass heading increments. Likelihoods are multinomial over the bins:
//   nominal: the residual is N(μ, σ²) (μ, σ fitted; a non-zero μ is reported as a bias);
//   compass_quantization: the residual sits on a lattice a + k·s blurred by N(0, σ_l²), with
//   weights following a normal envelope N(μ, τ²) — what the increment of a compass that reports
//   multiples of s looks like against a finer odometry heading.
// The held-out gain splits the counts in two halves by binomial thinning (seeded).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "algorithms/diagnosis/diagnosis.h"
#include "algorithms/diagnosis/ml_fit.h"
#include "core/chi_square.h"
#include "core/errors.h"
#include "core/input_limits.h"
#include "core/json_options.h"
#include "core/rng.h"
#include "core/skewness_kurtosis_normality.h"
#include "core/statistics.h"
#include "core/units.h"

namespace locbench::diagnosis {

ResidualHistogram read_histogram(const nlohmann::json& j, const std::string& file) {
  auto bad = [&](const std::string& what) { throw InputError(file, 0, what); };
  StrictJsonReader r(j, "", file);
  r.allow_only({"residual", "unit", "edges", "counts", "source"});
  for (const char* k : {"residual", "unit", "edges", "counts"}) r.required(k);
  ResidualHistogram h;
  r.read("residual", h.residual);
  r.read("unit", h.unit);
  double scale = 0.0;
  if (h.unit == "deg")
    scale = deg(1.0);
  else if (h.unit == "rad" || h.unit == "m")
    scale = 1.0;
  else if (h.unit == "mm")
    scale = mm(1.0);
  else
    bad("unit '" + h.unit + "': expected one of deg, rad, mm, m");
  if (!j["edges"].is_array() || !j["counts"].is_array()) bad("'edges' and 'counts' must be arrays of numbers");
  limits::check(static_cast<double>(j["counts"].size()), limits::kHistogramBins, file, "counts");
  if (j["edges"].size() != j["counts"].size() + 1) {
    bad(fmt::format("{} edges for {} counts: expected one edge more than counts", j["edges"].size(),
                    j["counts"].size()));
  }
  for (std::size_t i = 0; i < j["edges"].size(); ++i) {
    if (!j["edges"][i].is_number()) bad(fmt::format("edges[{}]: expected a number", i));
    const double e = j["edges"][i].get<double>();
    if (!(std::abs(e) <= 1e9)) bad(fmt::format("edges[{}]: {} is not a finite edge within ±1e9 {}", i, e, h.unit));
    h.edges.push_back(e * scale);
  }
  for (std::size_t i = 0; i < j["counts"].size(); ++i) {
    const auto& c = j["counts"][i];
    if (!c.is_number() || !(c.get<double>() >= 0.0) || c.get<double>() != std::floor(c.get<double>())) {
      bad(fmt::format("counts[{}]: expected a whole number of samples ≥ 0, found {}", i, c.dump()));
    }
    h.counts.push_back(c.get<double>());
  }
  if (h.counts.size() < 5) bad("too short: at least 5 bins needed");
  for (std::size_t i = 1; i < h.edges.size(); ++i) {
    if (!(h.edges[i] > h.edges[i - 1])) bad(fmt::format("edges[{}]: edges must increase", i));
  }
  double n = 0.0;
  std::size_t filled = 0;
  for (double c : h.counts) n += c, filled += c > 0.0 ? 1 : 0;
  limits::check(n, limits::kHistogramTotalCount, file, "counts (their sum)");
  limits::check(static_cast<double>(filled), limits::kHistogramFilledBins, file, "counts (bins > 0)");
  if (n < 30) bad(fmt::format("too few samples: {} counted, at least 30 needed", n));
  if (filled < 3) {
    bad(
        fmt::format("counts: only {} bin(s) hold samples; a distribution needs samples in at least 3 bins "
                    "(bins narrower than the residual's spread)",
                    filled));
  }
  return h;
}

namespace {

// Probability that a standard normal falls in [a, b], without cancellation in either tail.
double normal_mass(double a, double b) {
  constexpr double kInvSqrt2 = 0.70710678118654752440;
  if (a >= 0.0) return 0.5 * (std::erfc(a * kInvSqrt2) - std::erfc(b * kInvSqrt2));
  if (b <= 0.0) return 0.5 * (std::erfc(-b * kInvSqrt2) - std::erfc(-a * kInvSqrt2));
  return 1.0 - 0.5 * (std::erfc(-a * kInvSqrt2) + std::erfc(b * kInvSqrt2));
}

// A lattice point's blur is cut at ±8.5 σ_l (the mass beyond is below 2·10⁻¹⁷) and its envelope
// weight at ±12 τ (below e⁻⁷²): a lattice point then touches O(1 + σ_l/w) bins of width w, and the
// NLL costs O(bins + lattice points), not O(bins × lattice points). Bins without counts cost
// nothing (only the span's total mass is needed), so zero padding is free.
constexpr double kBlurCut = 8.5, kEnvelopeCut = 12.0;
// A blur wider than 2 steps leaves no lattice visible (ripple amplitude e^(-2π²·4) ≈ 10⁻³⁴); the
// fit has nothing to gain beyond it.
constexpr double kMaxBlurPerStep = 2.0;

// Multinomial NLL of `counts` under bin probabilities `p_of(j)`, normalised by `total` (the
// model's mass over the histogram's span); only bins with counts are evaluated.
template <typename BinProbability>
double multinomial_nll(const std::vector<double>& counts, double total, BinProbability p_of) {
  if (!(total > 0.0) || !std::isfinite(total)) return std::numeric_limits<double>::infinity();
  double nll = 0.0;
  for (std::size_t j = 0; j < counts.size(); ++j) {
    if (counts[j] > 0.0) nll -= counts[j] * std::log(std::max(p_of(j) / total, 1e-300));
  }
  return nll;
}

double normal_nll(const ResidualHistogram& h, const std::vector<double>& counts, double mu, double sigma) {
  if (!(sigma > 0.0)) return std::numeric_limits<double>::infinity();
  const double total = normal_mass((h.edges.front() - mu) / sigma, (h.edges.back() - mu) / sigma);
  return multinomial_nll(counts, total, [&](std::size_t j) {
    return normal_mass((h.edges[j] - mu) / sigma, (h.edges[j + 1] - mu) / sigma);
  });
}

// The lattice model: points a + k·s blurred by N(0, σ_l²), weighted by a normal envelope N(μ, τ²).
// When both the envelope and the blur are wide against the step, Poisson summation shows the
// mixture is N(μ, τ² + σ_l²) up to a ripple of relative amplitude e^(-2π² v / s²),
// v = τ²σ_l²/(τ² + σ_l²); for v ≥ 2 s² that is below 10⁻¹⁷ and the normal is used (O(bins)).
double lattice_nll(const ResidualHistogram& h, const std::vector<double>& counts, double a, double s, double sl,
                   double mu, double tau) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  if (!(s > 0.0 && sl > 0.0 && tau > 0.0) || sl > kMaxBlurPerStep * s) return inf;
  const double v = tau * tau * sl * sl / (tau * tau + sl * sl);
  if (v >= 2.0 * s * s) return normal_nll(h, counts, mu, std::sqrt(tau * tau + sl * sl));
  const double front = h.edges.front(), back = h.edges.back();
  const double lo = std::max(front - kBlurCut * sl, mu - kEnvelopeCut * tau);
  const double hi = std::min(back + kBlurCut * sl, mu + kEnvelopeCut * tau);
  const double klo = std::ceil((lo - a) / s), khi = std::floor((hi - a) / s);
  if (!(std::abs(klo) < 1e15 && std::abs(khi) < 1e15)) return inf;
  if (khi - klo > 4.0 * static_cast<double>(h.edges.size()) + 1e4) return inf;  // s ≥ w/2 bounds this
  // Bins that need a probability: those with counts (sorted edges, moving window per point).
  const std::size_t nb = counts.size();
  std::vector<double> mass(nb, 0.0);
  double total = 0.0;
  constexpr double kInvSqrt2 = 0.70710678118654752440;
  std::size_t first = 0;  // first edge ≥ c − cut, moves forward as c grows
  // Envelope weights by recurrence: w(k+1)/w(k) = r(k), r(k+1) = r(k)·q (two exp per call).
  const double c0 = a + klo * s;
  double w = std::exp(-0.5 * (c0 - mu) * (c0 - mu) / (tau * tau));
  double r = std::exp(-(c0 - mu) * s / (tau * tau) - 0.5 * s * s / (tau * tau));
  const double q = std::exp(-s * s / (tau * tau));
  for (double k = klo; k <= khi; k += 1.0, w *= r, r *= q) {
    const double c = a + k * s;
    // The point's mass inside the span: 1 unless it is within the blur cut of an end.
    const bool near_end = c - kBlurCut * sl < front || c + kBlurCut * sl > back;
    total += near_end ? w * normal_mass((front - c) / sl, (back - c) / sl) : w;
    while (first < h.edges.size() && h.edges[first] < c - kBlurCut * sl) ++first;
    // Tail probabilities at the edges within the cut; a bin's mass from two neighbouring edges.
    double z_prev = 0.0, t_prev = 0.0;
    bool have_prev = false;
    if (first > 0 && counts[first - 1] > 0.0) {  // the bin straddling the lower cut
      z_prev = -kBlurCut;
      t_prev = 0.0;
      have_prev = true;
    }
    std::size_t e = first;
    for (; e < h.edges.size() && h.edges[e] <= c + kBlurCut * sl; ++e) {
      const bool left = e > 0 && counts[e - 1] > 0.0, right = e < nb && counts[e] > 0.0;
      if (!left && !right) {
        have_prev = false;
        continue;
      }
      const double z = (h.edges[e] - c) / sl;
      const double t = 0.5 * std::erfc(std::abs(z) * kInvSqrt2);  // the tail beyond |z|
      if (left && have_prev) {
        // mass in [z_prev, z] from the tails: same side → difference, else 1 − both.
        const double m = z_prev >= 0.0 ? t_prev - t : (z <= 0.0 ? t - t_prev : 1.0 - t_prev - t);
        mass[e - 1] += w * m;
      }
      z_prev = z;
      t_prev = t;
      have_prev = true;
    }
    if (have_prev && e - 1 < nb && counts[e - 1] > 0.0 && e < h.edges.size()) {
      // The bin straddling the upper cut: everything above its lower edge.
      mass[e - 1] += w * (z_prev >= 0.0 ? t_prev : 1.0 - t_prev);
    }
  }
  return multinomial_nll(counts, total, [&](std::size_t j) { return mass[j]; });
}

std::vector<double> normal_probs(const ResidualHistogram& h, double mu, double sigma) {
  std::vector<double> p(h.counts.size());
  for (std::size_t j = 0; j < p.size(); ++j)
    p[j] = normal_mass((h.edges[j] - mu) / sigma, (h.edges[j + 1] - mu) / sigma);
  return p;
}

struct HistFits {
  FitResult normal0, normal, lattice;
};

HistFits fit_all(const ResidualHistogram& h, const std::vector<double>& counts) {
  std::vector<double> mids;
  for (std::size_t j = 0; j < counts.size(); ++j) mids.push_back(0.5 * (h.edges[j] + h.edges[j + 1]));
  double n = 0.0, m = 0.0, v = 0.0;
  for (std::size_t j = 0; j < counts.size(); ++j) n += counts[j], m += counts[j] * mids[j];
  m /= n;
  for (std::size_t j = 0; j < counts.size(); ++j) v += counts[j] * (mids[j] - m) * (mids[j] - m);
  const double sd = std::sqrt(v / n);
  const double width = h.edges[1] - h.edges[0];
  HistFits f;
  f.normal0 = fit_max_likelihood([&](const std::vector<double>& x) { return normal_nll(h, counts, 0.0, x[0]); },
                                 {{"sigma", sd, 0.0, true}});
  f.normal = fit_max_likelihood([&](const std::vector<double>& x) { return normal_nll(h, counts, x[0], x[1]); },
                                {{"mu", m, width * 0.01, false}, {"sigma", sd, 0.0, true}});
  // Lattice start: the step from the strongest period of the counts (2–4 bins), the offset at
  // the fullest bin.
  const std::size_t jmax = static_cast<std::size_t>(std::max_element(counts.begin(), counts.end()) - counts.begin());
  FitResult best;
  best.nll = std::numeric_limits<double>::infinity();
  for (int period = 2; period <= 4; ++period) {
    FitResult r = fit_max_likelihood(
        [&](const std::vector<double>& x) {
          if (x[1] < 0.5 * width) return std::numeric_limits<double>::infinity();
          return lattice_nll(h, counts, x[0], x[1], x[2], x[3], x[4]);
        },
        {{"offset", mids[jmax], width * 0.01, false},
         {"step", period * width, width * 0.01, false},
         {"sigma_lattice", 0.3 * width, 0.0, true},
         {"mu", m, width * 0.01, false},
         {"tau", sd, 0.0, true}});
    if (r.nll < best.nll || best.values.empty()) best = r;
  }
  f.lattice = best;
  return f;
}

}  // namespace

Diagnosis diagnose_histogram(const ResidualHistogram& h, const std::string& name, const DiagnosisOptions& options) {
  Diagnosis out;
  out.log = name;
  out.false_alarm = options.false_alarm;
  out.reference = "histogram of '" + h.residual + "' (" + h.unit + ")";
  out.nominal_model = {{"residual", h.residual}, {"distribution", "normal, zero mean (continuous sensors, no bias)"}};
  std::vector<double> mids;
  double n = 0.0;
  for (std::size_t j = 0; j < h.counts.size(); ++j)
    mids.push_back(0.5 * (h.edges[j] + h.edges[j + 1])), n += h.counts[j];

  const HistFits all = fit_all(h, h.counts);
  // The residual battery: the thesis's normality test (§3.2.1), bias, goodness of fit.
  const auto nt = skewness_kurtosis_test_binned(mids, h.counts, 0.1);
  out.residual_tests.push_back({"normality_skewness", h.residual, "", "u1", nt.u1, nt.p1, nt.g1});
  out.residual_tests.push_back({"normality_kurtosis", h.residual, "", "u2", nt.u2, nt.p2, nt.g2 - 3.0});
  const double lr_bias = 2.0 * (all.normal0.nll - all.normal.nll);
  out.residual_tests.push_back({"bias", h.residual, "", "likelihood_ratio", lr_bias,
                                chi_square_upper_tail(ChiSquareDof(1.0), lr_bias),
                                all.normal.values[0] / all.normal.values[1]});
  double pearson = 0.0;
  const auto p = normal_probs(h, all.normal.values[0], all.normal.values[1]);
  double ptot = 0.0;
  for (double v : p) ptot += v;
  for (std::size_t j = 0; j < p.size(); ++j) {
    const double e = n * p[j] / ptot;
    pearson += (h.counts[j] - e) * (h.counts[j] - e) / std::max(e, 1e-9);
  }
  const double dof = static_cast<double>(h.counts.size()) - 3.0;
  out.residual_tests.push_back({"goodness_of_fit_normal", h.residual, "", "pearson_chi2", pearson,
                                dof > 0.0 ? chi_square_upper_tail(ChiSquareDof(dof), pearson) : 1.0, pearson / n});
  const double lr_lat = 2.0 * (all.normal.nll - all.lattice.nll);
  out.residual_tests.push_back({"quantization_lattice", h.residual, "", "likelihood_ratio", lr_lat,
                                chi_square_upper_tail(ChiSquareDof(3.0), lr_lat), all.lattice.values[1]});
  const double level = options.false_alarm / static_cast<double>(out.residual_tests.size());
  for (auto& t : out.residual_tests) t.passed = t.p_value > level;

  // Held-out halves.
  Rng rng(1);
  std::vector<double> a(h.counts.size()), b(h.counts.size());
  for (std::size_t j = 0; j < h.counts.size(); ++j) {
    for (int k = 0; k < static_cast<int>(h.counts[j]); ++k) (rng.bernoulli(0.5) ? a : b)[j] += 1.0;
  }
  const HistFits fa = fit_all(h, a);
  double nb = 0.0;
  for (double v : b) nb += v;
  auto heldout_normal = normal_nll(h, b, fa.normal.values[0], fa.normal.values[1]) / nb;
  auto heldout_lattice = lattice_nll(h, b, fa.lattice.values[0], fa.lattice.values[1], fa.lattice.values[2],
                                     fa.lattice.values[3], fa.lattice.values[4]) /
                         nb;

  const double thr = chi_square_upper_quantile(ChiSquareDof(3.0), options.false_alarm);
  Cause q{"compass_quantization", "histogram", lr_lat >= thr};
  q.value = lr_lat;
  q.threshold = thr;
  const double to_unit = h.unit == "deg" ? to_deg(1.0) : h.unit == "mm" ? to_mm(1.0) : 1.0;
  q.parameters.push_back({"step_rad", all.lattice.values[1], all.lattice.ci_low[1], all.lattice.ci_high[1]});
  q.extra["step_in_histogram_unit"] = all.lattice.values[1] * to_unit;
  q.extra["lattice_offset_in_histogram_unit"] = all.lattice.values[0] * to_unit;
  q.extra["blur_sigma_in_histogram_unit"] = all.lattice.values[2] * to_unit;
  q.explanation = fmt::format(
      "the residual sits on a lattice of step {:.4g} {} (offset {:.3g} {}), blurred by σ = {:.3g} {}: the "
      "reference sensor reports multiples of the step, which a normal model of the residual misses",
      all.lattice.values[1] * to_unit, h.unit, all.lattice.values[0] * to_unit, h.unit, all.lattice.values[2] * to_unit,
      h.unit);
  q.gains.push_back({"heldout_nll_per_sample", heldout_normal, heldout_lattice});
  out.causes.push_back(q);
  if (q.detected) {
    out.detected.push_back(q.id);
    out.overall_gain = q.gains;
  }
  if (lr_bias >= chi_square_upper_quantile(ChiSquareDof(1.0), options.false_alarm)) {
    out.unexplained.push_back({"bias", h.residual, "", lr_bias, chi_square_upper_tail(ChiSquareDof(1.0), lr_bias),
                               all.normal.values[0] * to_unit,
                               "a histogram of one residual cannot tell its causes apart: wheel_diameter_ratio, "
                               "turn_rate_bias and compass_bias all shift it (confounded)"});
    out.confounded.push_back(
        {{"wheel_diameter_ratio", "turn_rate_bias", "compass_bias"},
         fmt::format("mean residual {:.4g} {} per sample", all.normal.values[0] * to_unit, h.unit),
         "a histogram has no distance, turn or time per sample, so a heading drift per sample cannot be "
         "attributed to unequal wheels (E_d), a turn-rate bias or a drifting compass"});
  }
  out.not_testable.push_back(
      "every cause but the residual's distribution: a histogram carries no time, distance or position");
  out.verdict = q.detected
                    ? fmt::format(
                          "The nominal (normal) model of {} misses a lattice of step {:.4g} {}: the residual is "
                          "quantized{}.",
                          h.residual, all.lattice.values[1] * to_unit, h.unit,
                          out.unexplained.empty()
                              ? ""
                              : fmt::format(", and it has a bias of {:.3g} {} per sample no single cause explains",
                                            all.normal.values[0] * to_unit, h.unit))
                    : (out.unexplained.empty()
                           ? fmt::format("No significant discrepancy: the histogram of {} is consistent with a "
                                         "zero-mean normal residual at a false-alarm level of {}.",
                                         h.residual, options.false_alarm)
                           : fmt::format("The residual {} has a bias of {:.3g} {} per sample no single cause explains.",
                                         h.residual, all.normal.values[0] * to_unit, h.unit));
  return out;
}

}  // namespace locbench::diagnosis
