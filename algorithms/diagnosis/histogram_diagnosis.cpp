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

#include "algorithms/core/errors.h"
#include "algorithms/core/rng.h"
#include "algorithms/core/statistics.h"
#include "algorithms/core/units.h"
#include "algorithms/diagnosis/diagnosis.h"
#include "algorithms/diagnosis/ml_fit.h"
#include "algorithms/slip/normality_test.h"

namespace locbench::diagnosis {

ResidualHistogram read_histogram(const nlohmann::json& j, const std::string& file) {
  auto bad = [&](const std::string& what) { throw InputError(file, 0, what); };
  if (!j.is_object()) bad("expected a JSON object {\"residual\", \"unit\", \"edges\", \"counts\"}");
  for (const char* k : {"residual", "unit", "edges", "counts"}) {
    if (!j.contains(k)) bad(std::string("missing key '") + k + "'");
  }
  for (const auto& [k, v] : j.items()) {
    if (k != "residual" && k != "unit" && k != "edges" && k != "counts" && k != "source") bad("unknown key '" + k + "'");
  }
  ResidualHistogram h;
  if (!j["residual"].is_string() || !j["unit"].is_string()) bad("'residual' and 'unit' must be strings");
  h.residual = j["residual"].get<std::string>();
  h.unit = j["unit"].get<std::string>();
  double scale = 0.0;
  if (h.unit == "deg") scale = deg(1.0);
  else if (h.unit == "rad" || h.unit == "m") scale = 1.0;
  else if (h.unit == "mm") scale = mm(1.0);
  else bad("unit '" + h.unit + "': expected one of deg, rad, mm, m");
  if (!j["edges"].is_array() || !j["counts"].is_array()) bad("'edges' and 'counts' must be arrays of numbers");
  for (std::size_t i = 0; i < j["edges"].size(); ++i) {
    if (!j["edges"][i].is_number()) bad(fmt::format("edges[{}]: expected a number", i));
    h.edges.push_back(j["edges"][i].get<double>() * scale);
  }
  for (std::size_t i = 0; i < j["counts"].size(); ++i) {
    if (!j["counts"][i].is_number() || j["counts"][i].get<double>() < 0.0) bad(fmt::format("counts[{}]: expected a non-negative number", i));
    h.counts.push_back(j["counts"][i].get<double>());
  }
  if (h.edges.size() != h.counts.size() + 1) {
    bad(fmt::format("{} edges for {} counts: expected one edge more than counts", h.edges.size(), h.counts.size()));
  }
  if (h.counts.size() < 5) bad("too short: at least 5 bins needed");
  for (std::size_t i = 1; i < h.edges.size(); ++i) {
    if (!(h.edges[i] > h.edges[i - 1])) bad(fmt::format("edges[{}]: edges must increase", i));
  }
  double n = 0.0;
  for (double c : h.counts) n += c;
  if (n < 30) bad(fmt::format("too few samples: {} counted, at least 30 needed", n));
  return h;
}

namespace {

double phi(double z) { return 1.0 - normal_upper_tail(z); }

// Bin probabilities of the lattice model (envelope weights over lattice points within range).
std::vector<double> lattice_probs(const ResidualHistogram& h, double a, double s, double sl, double mu, double tau) {
  const double lo = h.edges.front() - 4 * sl, hi = h.edges.back() + 4 * sl;
  std::vector<double> p(h.counts.size(), 0.0);
  if (!(s > 0.0) || (hi - lo) / s > 2000) return p;
  const long k0 = static_cast<long>(std::floor((lo - a) / s)), k1 = static_cast<long>(std::ceil((hi - a) / s));
  for (long k = k0; k <= k1; ++k) {
    const double c = a + static_cast<double>(k) * s;
    const double w = std::exp(-0.5 * (c - mu) * (c - mu) / (tau * tau));
    for (std::size_t j = 0; j < p.size(); ++j) p[j] += w * (phi((h.edges[j + 1] - c) / sl) - phi((h.edges[j] - c) / sl));
  }
  return p;
}

std::vector<double> normal_probs(const ResidualHistogram& h, double mu, double sigma) {
  std::vector<double> p(h.counts.size());
  for (std::size_t j = 0; j < p.size(); ++j) p[j] = phi((h.edges[j + 1] - mu) / sigma) - phi((h.edges[j] - mu) / sigma);
  return p;
}

double multinomial_nll(const std::vector<double>& counts, std::vector<double> p) {
  double total = 0.0;
  for (double v : p) total += v;
  if (!(total > 0.0)) return std::numeric_limits<double>::infinity();
  double nll = 0.0;
  for (std::size_t j = 0; j < p.size(); ++j) {
    if (counts[j] > 0.0) nll -= counts[j] * std::log(std::max(p[j] / total, 1e-300));
  }
  return nll;
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
  f.normal0 = fit_max_likelihood([&](const std::vector<double>& x) { return multinomial_nll(counts, normal_probs(h, 0.0, x[0])); },
                                 {{"sigma", sd, 0.0, true}});
  f.normal = fit_max_likelihood([&](const std::vector<double>& x) { return multinomial_nll(counts, normal_probs(h, x[0], x[1])); },
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
          return multinomial_nll(counts, lattice_probs(h, x[0], x[1], x[2], x[3], x[4]));
        },
        {{"offset", mids[jmax], width * 0.01, false},
         {"step", period * width, width * 0.01, false},
         {"sigma_lattice", 0.3 * width, 0.0, true},
         {"mu", m, width * 0.01, false},
         {"tau", sd, 0.0, true}});
    if (r.nll < best.nll) best = r;
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
  for (std::size_t j = 0; j < h.counts.size(); ++j) mids.push_back(0.5 * (h.edges[j] + h.edges[j + 1])), n += h.counts[j];

  const HistFits all = fit_all(h, h.counts);
  // The residual battery: the thesis's normality test (§3.2.1), bias, goodness of fit.
  const auto nt = skewness_kurtosis_test_binned(mids, h.counts, 0.1);
  out.residual_tests.push_back({"normality_skewness", h.residual, "", "u1", nt.u1, nt.p1, nt.g1});
  out.residual_tests.push_back({"normality_kurtosis", h.residual, "", "u2", nt.u2, nt.p2, nt.g2 - 3.0});
  const double lr_bias = 2.0 * (all.normal0.nll - all.normal.nll);
  out.residual_tests.push_back({"bias", h.residual, "", "likelihood_ratio", lr_bias, chi2_upper_p(lr_bias, 1.0),
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
  out.residual_tests.push_back({"goodness_of_fit_normal", h.residual, "", "pearson_chi2", pearson, chi2_upper_p(pearson, dof), pearson / n});
  const double lr_lat = 2.0 * (all.normal.nll - all.lattice.nll);
  out.residual_tests.push_back({"quantization_lattice", h.residual, "", "likelihood_ratio", lr_lat, chi2_upper_p(lr_lat, 3.0),
                                all.lattice.values[1]});
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
  auto heldout_normal = multinomial_nll(b, normal_probs(h, fa.normal.values[0], fa.normal.values[1])) / nb;
  auto heldout_lattice = multinomial_nll(b, lattice_probs(h, fa.lattice.values[0], fa.lattice.values[1], fa.lattice.values[2],
                                                          fa.lattice.values[3], fa.lattice.values[4])) / nb;

  const double thr = chi2_quantile(1.0 - options.false_alarm, 3.0);
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
      all.lattice.values[1] * to_unit, h.unit, all.lattice.values[0] * to_unit, h.unit, all.lattice.values[2] * to_unit, h.unit);
  q.gains.push_back({"heldout_nll_per_sample", heldout_normal, heldout_lattice});
  out.causes.push_back(q);
  if (q.detected) {
    out.detected.push_back(q.id);
    out.overall_gain = q.gains;
  }
  if (lr_bias >= chi2_quantile(1.0 - options.false_alarm, 1.0)) {
    out.unexplained.push_back({"bias", h.residual, "", lr_bias, chi2_upper_p(lr_bias, 1.0), all.normal.values[0] * to_unit});
    out.confounded.push_back(
        {{"wheel_diameter_ratio", "turn_rate_bias", "compass_bias"},
         fmt::format("mean residual {:.4g} {} per sample", all.normal.values[0] * to_unit, h.unit),
         "a histogram has no distance, turn or time per sample, so a heading drift per sample cannot be "
         "attributed to unequal wheels (E_d), a turn-rate bias or a drifting compass"});
  }
  out.not_testable.push_back("every cause but the residual's distribution: a histogram carries no time, distance or position");
  out.verdict = q.detected
      ? fmt::format("The nominal (normal) model of {} misses a lattice of step {:.4g} {}: the residual is "
                    "quantized{}.", h.residual, all.lattice.values[1] * to_unit, h.unit,
                    out.unexplained.empty() ? "" : fmt::format(", and it has a bias of {:.3g} {} per sample no single cause explains",
                                                               all.normal.values[0] * to_unit, h.unit))
      : (out.unexplained.empty() ? fmt::format("No significant discrepancy: the histogram of {} is consistent with a "
                                               "zero-mean normal residual at a false-alarm level of {}.", h.residual, options.false_alarm)
                                 : fmt::format("The residual {} has a bias of {:.3g} {} per sample no single cause explains.",
                                               h.residual, all.normal.values[0] * to_unit, h.unit));
  return out;
}

}  // namespace locbench::diagnosis
