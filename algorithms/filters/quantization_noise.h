#pragma once
// Encoder quantization error (eq. 4.12–4.21) and its Gaussian stand-in (eq. 4.27–4.35).
// U = C N and U_act = U + e_k − e_{k+1} with e_k, e_{k+1} independent and uniform on [0, C], so
// e = e_k − e_{k+1} has the triangular density f₁(e) = (C − |e|)/C² on [−C, C] (eq. 4.18), mean
// 0 and variance C²/6 (eq. 4.21). The thesis replaces f₁ by the N(0, σ²) density f₂ with the σ
// that minimises G₂(σ) = ∫(f₁ − f₂)² dx (eq. 4.28). Every function is unit-agnostic: C and σ in
// the same length unit; G₂ comes out in 1/unit, G₁ is dimensionless. README.md compares the
// results with the published σ = 5.00 mm, G₂ = 0.0021.
namespace locbench::filters {

// f₁(e) (eq. 4.18).
double triangular_density(double e, double c);
// D(e) = C²/6 (eq. 4.21).
double quantization_variance(double c);
// The σ with the same variance as f₁: C/√6.
double moment_matched_sigma(double c);

// G₂(σ) = ∫(f₁ − f₂)² dx, exactly: 2/(3C) + 1/(2√π σ) − (2/C) erf(C/(√2 σ))
//   + 4σ/(√(2π) C²) (1 − exp(−C²/(2σ²))).
double l2_distance(double sigma, double c);
// dG₂/dσ = −1/(2√π σ²) + 4(1 − exp(−C²/(2σ²)))/(√(2π) C²).
double l2_distance_derivative(double sigma, double c);
// argmin_σ G₂ by Brent's method on [0.05 C, 2 C] (relative tolerance ~1e-8).
double l2_optimal_sigma(double c);
// The same optimum in closed form: dG₂/dσ = 0 ⇔ 1 − e^{−t} = t/(2√2) with t = C²/(2σ²), whose
// non-zero root is t* = 2√2 + W₀(−2√2 e^{−2√2}) (Lambert W), so σ* = C/√(2t*) ≈ 0.43659 C.
double l2_optimal_sigma_closed_form(double c);

// The thesis's objective g(σ) of eq. 4.35 (its sign typos in the exponents corrected):
// 1/(4√π σ) − (1/C)√(1 − e^{−C²/(2σ²)}) + √2 σ/(√π C²)(1 − e^{−C²/(2σ²)}). Eq. 4.31–4.33 take
// (∫₀^C e^{−x²/(2σ²)} dx)² over the quarter disc of radius C instead of the square [0, C]²,
// i.e. they replace erf(C/(√2σ)) by √(1 − e^{−C²/(2σ²)}); g is therefore not G₂/2 − 1/(3C).
double thesis_objective(double sigma, double c);
// The G₂ the thesis reports: 2(g(σ) + ∫₀^∞ f₁² dx) = 2(g(σ) + 1/(3C)).
double thesis_l2_distance(double sigma, double c);
// argmin_σ g(σ), Brent's method.
double thesis_optimal_sigma(double c);

// G₁(σ) = ∫|f₁ − f₂| dx (eq. 4.27, the area between the curves), exactly: the crossings of f₁
// and f₂ on (0, C) are bracketed and refined by root finding; the pieces are integrated in
// closed form (polynomial and normal CDF).
double l1_distance(double sigma, double c);
// argmin_σ G₁ by Brent's method. Eq. 4.28 claims minimising G₂ "is the same as" minimising G₁:
// it is not (see README.md).
double l1_optimal_sigma(double c);

// Every candidate σ for one encoder, for reports. Units as given (mm in, mm and 1/mm out).
struct QuantizationSigmaComparison {
  double c = 0.0;                       // encoder resolution
  double variance = 0.0;                // C²/6
  double moment_matched_sigma = 0.0;    // C/√6
  double l2_optimal_sigma = 0.0;        // exact argmin G₂
  double l2_at_optimum = 0.0;           // G₂ there
  double l2_at_moment_matched = 0.0;    // G₂(C/√6)
  double thesis_optimal_sigma = 0.0;    // argmin of eq. 4.35
  double thesis_l2_at_published = 0.0;  // the thesis's G₂ formula at the published σ
  double l2_at_published = 0.0;         // exact G₂ at the published σ
  double l1_optimal_sigma = 0.0;        // exact argmin G₁
  double l1_at_l1_optimum = 0.0;
  double published_sigma = 0.0;  // as given
  double published_l2 = 0.0;     // as given
};
QuantizationSigmaComparison compare_quantization_sigma(double c, double published_sigma, double published_l2);

}  // namespace locbench::filters
