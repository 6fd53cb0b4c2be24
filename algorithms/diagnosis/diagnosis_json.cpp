// The diagnosis report, "schema": "locbench.diagnosis/1" (README, "Diagnosis").
#include <cmath>

#include "algorithms/diagnosis/diagnosis.h"
#include "core/errors.h"
#include "core/json_options.h"

namespace locbench::diagnosis {
namespace {

nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json gain_json(const Gain& g) {
  return {{"metric", g.metric},
          {"before", number(g.before)},
          {"after", number(g.after)},
          {"relative", number(g.relative())}};
}

}  // namespace

nlohmann::json to_json(const Diagnosis& d) {
  nlohmann::json j;
  j["schema"] = "locbench.diagnosis/1";
  j["log"] = d.log;
  j["reference"] = d.reference;
  j["nominal_model"] = d.nominal_model;
  j["false_alarm"] = d.false_alarm;
  j["residual_tests"] = nlohmann::json::array();
  for (const auto& t : d.residual_tests) {
    j["residual_tests"].push_back({{"name", t.name},
                                   {"residual", t.residual},
                                   {"variable", t.variable},
                                   {"statistic", t.statistic},
                                   {"value", number(t.value)},
                                   {"p_value", number(t.p_value)},
                                   {"strength", number(t.strength)},
                                   {"passed", t.passed}});
  }
  j["causes"] = nlohmann::json::array();
  for (const auto& c : d.causes) {
    nlohmann::json cj{
        {"id", c.id},
        {"channel", c.channel},
        {"detected", c.detected},
        {"evidence", {{"statistic", c.statistic}, {"value", number(c.value)}, {"threshold", number(c.threshold)}}},
        {"parameters", nlohmann::json::object()},
        {"identifiable", c.identifiable},
        {"explanation", c.explanation}};
    if (c.validated) cj["evidence"]["heldout_validated"] = *c.validated;
    for (const auto& p : c.parameters) {
      cj["parameters"][p.name] = {{"value", number(p.value)}, {"ci95", {number(p.lo), number(p.hi)}}};
    }
    for (const auto& [k, v] : c.extra.items()) cj["parameters"][k] = v;
    if (!c.gains.empty()) {
      cj["gain"] = gain_json(c.gains.front());
      for (std::size_t i = 1; i < c.gains.size(); ++i) cj["gain"]["also"].push_back(gain_json(c.gains[i]));
    } else {
      cj["gain"] = nullptr;
    }
    j["causes"].push_back(cj);
  }
  j["detected"] = d.detected;
  j["unexplained"] = nlohmann::json::array();
  for (const auto& u : d.unexplained) {
    j["unexplained"].push_back({{"test", u.test},
                                {"residual", u.residual},
                                {"variable", u.variable},
                                {"statistic", number(u.statistic)},
                                {"p_value", number(u.p_value)},
                                {"strength", number(u.strength)},
                                {"reason", u.reason}});
  }
  j["unconfirmed"] = d.unconfirmed;
  j["confounded"] = nlohmann::json::array();
  for (const auto& g : d.confounded) {
    j["confounded"].push_back({{"ids", g.ids}, {"combination", g.combination}, {"explanation", g.explanation}});
  }
  j["not_testable"] = d.not_testable;
  j["gain"] = nlohmann::json::array();
  for (const auto& g : d.overall_gain) j["gain"].push_back(gain_json(g));
  j["noise_floor"] = {{"window_s", d.noise_window_s},
                      {"sigma_x_m", number(d.noise_sigma_x)},
                      {"sigma_y_m", number(d.noise_sigma_y)},
                      {"sigma_theta_rad", number(d.noise_sigma_theta)}};
  j["verdict"] = d.verdict;
  if (d.odometry_model || d.landmark_model) {
    nlohmann::json models = nlohmann::json::object();
    if (d.odometry_model) {
      models["odometry_kind"] = d.odometry_kind;
      models["odometry_window_s"] = d.noise_window_s;
      models["odometry"] = *d.odometry_model;
    }
    if (d.landmark_model) models["landmark"] = *d.landmark_model;
    j["models"] = models;
  }
  return j;
}

FittedModels read_fitted_models(const nlohmann::json& report_or_models) {
  const bool report = report_or_models.is_object() && report_or_models.contains("schema");
  if (report && !report_or_models.contains("models")) throw UsageError("diagnosis report: no \"models\" object");
  const nlohmann::json& j = report ? report_or_models.at("models") : report_or_models;
  StrictJsonReader r(j, "models");
  FittedModels out;
  r.read("odometry_kind", out.odometry_kind);
  r.read("odometry_window_s", out.odometry_window_s);
  if (const nlohmann::json* v = r.raw("odometry")) out.odometry = v->get<OdometryModel>();
  if (const nlohmann::json* v = r.raw("landmark")) out.landmark = v->get<LandmarkModel>();
  r.finish();
  if (out.odometry && out.odometry_kind != "encoder" && out.odometry_kind != "velocity") {
    throw UsageError("models.odometry_kind: expected \"encoder\" or \"velocity\", got \"" + out.odometry_kind + "\"");
  }
  if (!(out.odometry_window_s > 0.0)) throw UsageError("models.odometry_window_s: expected > 0 s");
  return out;
}

}  // namespace locbench::diagnosis
