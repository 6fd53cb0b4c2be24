#include "experiment_framework/plot_series.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "core/units.h"

namespace locbench::experiments {

reports::PlotSeries trajectory_series(const std::string& name, const Trajectory& t, std::size_t max_points) {
  reports::PlotSeries s;
  s.name = name;
  const auto& poses = t.poses();
  if (poses.empty()) return s;
  const std::size_t stride = std::max<std::size_t>(1, (poses.size() + max_points - 1) / max_points);
  for (std::size_t i = 0; i < poses.size(); i += stride) {
    s.x.push_back(poses[i].pose.x);
    s.y.push_back(poses[i].pose.y);
  }
  if ((poses.size() - 1) % stride != 0) {
    s.x.push_back(poses.back().pose.x);
    s.y.push_back(poses.back().pose.y);
  }
  return s;
}

std::vector<double> distance_grid(double total, double step) {
  std::vector<double> g;
  if (!(step > 0.0)) return g;
  for (int i = 0; i * step <= total + 1e-9; ++i) g.push_back(i * step);
  return g;
}

std::vector<double> error_at_distances(const Trajectory& truth, const Trajectory& estimate,
                                       const std::vector<double>& distances) {
  std::vector<double> out(distances.size(), std::numeric_limits<double>::quiet_NaN());
  const auto& poses = truth.poses();
  double travelled = 0.0;
  std::size_t next = 0;
  for (std::size_t i = 0; i < poses.size() && next < distances.size(); ++i) {
    if (i > 0) {
      travelled += std::hypot(poses[i].pose.x - poses[i - 1].pose.x, poses[i].pose.y - poses[i - 1].pose.y);
    }
    while (next < distances.size() && travelled >= distances[next]) {
      if (const auto e = estimate.pose_at(poses[i].t)) {
        out[next] = std::hypot(e->x - poses[i].pose.x, e->y - poses[i].pose.y);
      }
      ++next;
    }
  }
  return out;
}

reports::PlotSeries mean_over_runs(const std::string& name, const std::vector<double>& distances,
                                   const std::vector<std::vector<double>>& runs) {
  reports::PlotSeries s;
  s.name = name;
  for (std::size_t i = 0; i < distances.size(); ++i) {
    double sum = 0.0;
    int n = 0;
    for (const auto& r : runs) {
      if (i < r.size() && std::isfinite(r[i])) {
        sum += r[i];
        ++n;
      }
    }
    if (n == 0) continue;
    s.x.push_back(distances[i]);
    s.y.push_back(sum / n);
  }
  return s;
}

reports::Plot run_zero_trajectories(const std::string& what, std::uint64_t seed,
                                    std::vector<reports::PlotSeries> paths) {
  return {"trajectories_run_0",
          "trajectory",
          "Trajectories of run 0: " + what,
          "x",
          "m",
          "y",
          "m",
          std::move(paths),
          "Monte-Carlo run 0 (seed " + std::to_string(seed) + ")"};
}

reports::Plot mean_error_vs_distance(const std::vector<std::string>& methods,
                                     const std::vector<std::vector<std::vector<double>>>& errors, double step) {
  const std::size_t runs = errors.empty() ? 0 : errors.front().size();
  reports::Plot plot{"error_vs_distance",
                     "error_vs_distance",
                     "Position error against distance travelled (mean over runs)",
                     "distance travelled",
                     "m",
                     "position error",
                     "m",
                     {},
                     fmt::format("mean over {} Monte-Carlo runs, every {:g} m of the true path", runs, step)};
  std::size_t longest = 0;
  for (const auto& method : errors) {
    for (const auto& run : method) longest = std::max(longest, run.size());
  }
  const std::vector<double> grid = distance_grid(step * static_cast<double>(longest), step);
  for (std::size_t m = 0; m < methods.size() && m < errors.size(); ++m) {
    plot.series.push_back(mean_over_runs(methods[m], grid, errors[m]));
  }
  return plot;
}

}  // namespace locbench::experiments

namespace locbench::experiments {

reports::PlotSeries cdf_samples(const std::string& name, std::vector<double> values, std::size_t n) {
  reports::PlotSeries s;
  s.name = name;
  std::erase_if(values, [](double v) { return !std::isfinite(v); });
  std::sort(values.begin(), values.end());
  if (values.size() <= n || n < 2) {
    s.y = std::move(values);
    return s;
  }
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t k = (i * (values.size() - 1) + (n - 1) / 2) / (n - 1);
    s.y.push_back(values[k]);
  }
  return s;
}

reports::Plot error_cdf_plot(std::string name, std::string title, std::string x_label, std::string x_unit,
                             std::vector<reports::PlotSeries> samples, std::string note) {
  return {std::move(name),       "cdf", std::move(title),   std::move(x_label), std::move(x_unit),
          "fraction of samples", "",    std::move(samples), std::move(note)};
}

std::vector<reports::Plot> relative_pose_error_cdfs(const std::string& dataset, const std::string& what,
                                                    const std::vector<std::string>& methods,
                                                    const std::vector<std::vector<double>>& translation_m,
                                                    const std::vector<std::vector<double>>& rotation_rad,
                                                    const std::string& note) {
  const auto scaled = [](std::vector<double> v, double factor) {
    for (double& e : v) e *= factor;
    return v;
  };
  std::vector<reports::PlotSeries> trans, rot;
  for (std::size_t m = 0; m < methods.size(); ++m) {
    trans.push_back(cdf_samples(methods[m], scaled(translation_m.at(m), to_mm(1.0))));
    rot.push_back(cdf_samples(methods[m], scaled(rotation_rad.at(m), to_deg(1.0))));
  }
  std::vector<reports::Plot> plots;
  plots.push_back(error_cdf_plot(reports::key_part(dataset + "_rpe_translation_cdf"),
                                 dataset + ": " + what + " translation error", "translation error", "mm",
                                 std::move(trans), note));
  plots.push_back(error_cdf_plot(reports::key_part(dataset + "_rpe_rotation_cdf"),
                                 dataset + ": " + what + " rotation error", "rotation error", "deg", std::move(rot),
                                 note));
  return plots;
}

reports::PlotSeries binned_means(const std::string& name, const std::vector<double>& x, const std::vector<double>& y,
                                 std::size_t bins) {
  reports::PlotSeries s;
  s.name = name;
  std::vector<std::pair<double, double>> xy;
  for (std::size_t i = 0; i < std::min(x.size(), y.size()); ++i) {
    if (std::isfinite(x[i]) && std::isfinite(y[i])) xy.emplace_back(x[i], y[i]);
  }
  std::sort(xy.begin(), xy.end());
  bins = std::max<std::size_t>(1, std::min(bins, xy.size() / 3));
  for (std::size_t b = 0; b < bins && !xy.empty(); ++b) {
    const std::size_t lo = b * xy.size() / bins, hi = (b + 1) * xy.size() / bins;
    if (hi - lo < 3) continue;
    double sx = 0.0, sy = 0.0;
    for (std::size_t i = lo; i < hi; ++i) {
      sx += xy[i].first;
      sy += xy[i].second;
    }
    s.x.push_back(sx / static_cast<double>(hi - lo));
    s.y.push_back(sy / static_cast<double>(hi - lo));
  }
  return s;
}

}  // namespace locbench::experiments
