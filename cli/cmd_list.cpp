// `locbench list`: experiments, simulator scenarios, and the real datasets found with their
// record counts and time spans. `locbench list LOG`: what locbench reads from one log; for a ROS
// bag, every topic with its type, count and rate, and the topics locbench uses.
#include <fmt/format.h>

#include <iostream>

#include "algorithms/calibration/calibration_data.h"
#include "cli/bag_topic_options.h"
#include "cli/commands.h"
#include "core/errors.h"
#include "datasets/catalog/calibration_catalog.h"
#include "datasets/catalog/data_root.h"
#include "datasets/catalog/dataset_catalog.h"
#include "datasets/io/bag_log.h"
#include "datasets/io/log_loader.h"
#include "datasets/sim/presets.h"
#include "experiment_framework/experiment.h"

namespace locbench::cli {
using locbench::catalog::calibration_dataset_parts, locbench::catalog::dataset_catalog, locbench::catalog::DatasetEntry,
    locbench::catalog::is_calibration_dataset, locbench::catalog::load_catalog_calibration_records,
    locbench::catalog::load_catalog_dataset;
namespace {

struct ListArgs {
  BagTopicArgs topics;  // --odom, --truth, --scan, --heading, --joints
  std::string log;
  std::string data;
  bool no_load = false;
};

std::string counts(const Log& log) {
  std::string s;
  auto add = [&s](std::size_t n, const char* what) {
    if (n == 0) return;
    if (!s.empty()) s += ", ";
    s += fmt::format("{} {}", n, what);
  };
  add(log.odometry.size(), "ODOM");
  add(log.encoders.size(), "ENCODER");
  add(log.compass.size(), "COMPASS");
  add(log.laser.size(), "FLASER");
  add(log.truth.size(), "TRUEPOS");
  add(log.landmarks.size(), "landmark");
  add(log.relations.size(), "relations");
  return s;
}

void print_bag(const io::BagSpec& spec) {
  const io::BagDescription d = io::describe_bag(spec);
  std::cout << fmt::format("{} {}: {} topics\n", d.format, spec.path.string(), d.topics.size());
  std::cout << fmt::format("  {:<28} {:<40} {:>8} {:>10}  {}\n", "topic", "type", "messages", "rate", "used as");
  for (const io::BagTopicUse& t : d.topics) {
    const std::string rate = t.rate > 0.0 ? fmt::format("{:.4g}", t.rate) : "-";
    std::cout << fmt::format("  {:<28} {:<40} {:>8} {:>7} Hz  {}\n", t.topic.name, t.topic.type, t.topic.count, rate,
                             t.role.empty() ? "-" : t.role);
  }
  for (const std::string& n : d.notes) std::cout << "  " << n << "\n";
}

// One log: for a bag its topics, then (any log) the records locbench reads from it.
int list_log(const ListArgs& args) {
  if (const auto bag = io::parse_bag_spec(args.log)) {
    if (!std::filesystem::exists(bag->path)) throw InputError(bag->path.string(), 0, "no such file or folder");
    print_bag(*bag);
  }
  const Log log = io::load_log(args.log);
  const auto [t0, t1] = log.time_span();
  std::cout << fmt::format("{}: {:.3f} s from t = {:.3f}: {}\n", args.log, t1 - t0, t0, counts(log));
  return kExitOk;
}

int list(const ListArgs& args) {
  if (!args.log.empty()) return list_log(args);
  std::cout << "Experiments (* = default suite):\n";
  for (const auto& e : experiments::all_experiments()) {
    std::cout << fmt::format("  {} {:<26} {}\n", e->in_default_suite() ? '*' : ' ', e->name(), e->description());
  }
  std::cout << "\nMethods (the name each has in result keys; thesis = proposed, baseline = compared against):\n";
  struct Method {
    const char* name;
    const char* where;
    const char* what;
  };
  static constexpr Method kMethods[] = {
      {"umbmark_classic", "baselines/calibration", "baseline: Borenstein & Feng's UMBmark (eq. 2.3–2.13)"},
      {"umbmark_improved", "algorithms/calibration", "thesis: improved UMBmark (eq. 2.16–2.27)"},
      {"ml", "algorithms/calibration", "ours: maximum-likelihood odometry + sensor-pose calibration"},
      {"slip_detector", "algorithms/slip", "thesis: compass slip detection and correction (eq. 3.3–3.17)"},
      {"ikf_*", "algorithms/slip", "thesis: indirect Kalman filter for S_L, S_R, δB (eq. 3.18–3.26)"},
      {"adaptive_model_ekf", "algorithms/filters",
       "thesis: compass EKF with the adaptive odometry noise (eq. 4.36–4.44)"},
      {"fixed_q_ekf", "baselines/filters", "baseline: EKF with fixed Q"},
      {"sage_husa_aekf", "baselines/filters", "baseline: Sage–Husa AEKF (Deng forgetting, Zhang fix)"},
      {"vb_akf", "baselines/filters", "baseline: variational-Bayes AKF (Särkkä & Nummenmaa 2009)"},
      {"eap", "algorithms/laser", "thesis: Effective-Area-of-Plane matcher (eq. 5.6–5.17); eap_indexed: + grid index"},
      {"split_and_merge", "baselines/laser", "baseline: split-and-merge extraction + line-to-map matching"},
      {"agglomerative", "baselines/laser", "baseline: agglomerative (Arras-style) clustering + matching"},
      {"rwht", "baselines/laser", "baseline: Range Weighted Hough Transform (Forsberg et al.)"},
      {"point_to_line, point_to_point", "algorithms/pose_correction", "thesis: position correction (eq. 6.22–6.38)"},
      {"ekf_eap", "algorithms/pose_correction", "thesis: EKF tracker fusing odometry and corrections (eq. 6.39–6.42)"},
      {"kalman_line_features", "baselines/localization", "baseline: the slides' (α, r) line-feature Kalman localizer"},
  };
  for (const Method& m : kMethods) {
    std::cout << fmt::format("    {:<26} {:<27} {}\n", m.name, m.where, m.what);
  }
  std::cout << "\nSimulator scenarios (locbench simulate NAME):\n";
  for (const sim::PresetInfo& p : sim::preset_list()) {
    std::cout << fmt::format("    {:<26} {}\n", p.name, p.description);
  }
  const std::filesystem::path root = args.data.empty() ? catalog::data_root() : std::filesystem::path(args.data);
  std::cout << "\nDatasets under " << root.string() << ":\n";
  for (const DatasetEntry& d : dataset_catalog()) {
    const std::string path = (root / d.path).string();
    if (!std::filesystem::exists(path.substr(0, path.find('#')))) {
      std::cout << fmt::format("    {:<26} absent ({})\n", d.name, d.path);
      continue;
    }
    if (is_calibration_dataset(d)) {
      std::string parts;
      std::size_t samples = 0;
      try {
        for (const std::string& part : calibration_dataset_parts(d)) {
          samples += calibration::calibration_data_from_records(load_catalog_calibration_records(d, root, part))
                         .samples.size();
          parts += (parts.empty() ? "" : ", ") + (part.empty() ? std::string("all") : part);
        }
        std::cout << fmt::format("    {:<26} calibration samples: {} ({})\n", d.name, samples, parts);
      } catch (const InputError& e) {
        std::cout << fmt::format("    {:<26} unreadable: {}\n", d.name, e.what());
      }
      continue;
    }
    if (!d.reader_pending.empty()) {
      std::cout << fmt::format("    {:<26} present; reader arrives with {}\n", d.name, d.reader_pending);
      continue;
    }
    if (args.no_load) {
      std::cout << fmt::format("    {:<26} present\n", d.name);
      continue;
    }
    try {
      const Log log = load_catalog_dataset(d, root);
      const auto [t0, t1] = log.time_span();
      std::cout << fmt::format("    {:<26} {:.1f} s from t = {:.3f}: {}\n", d.name, t1 - t0, t0, counts(log));
    } catch (const InputError& e) {
      std::cout << fmt::format("    {:<26} unreadable: {}\n", d.name, e.what());
    }
  }
  return kExitOk;
}

}  // namespace

Action add_list_command(CLI::App& app) {
  const auto [cmd, args] = add_verb<ListArgs>(app, "list", "List experiments, scenarios and datasets found");
  cmd->add_option("log", args->log,
                  "A log to describe instead: its records; for a ROS bag (LOG.bag, a ROS 2 bag folder) every topic "
                  "with type, count and rate, and which ones locbench uses (choose with LOG#odom=…,truth=…,scan=…)");
  add_data_option(cmd, args->data);
  cmd->add_flag("--no-load", args->no_load, "Only check that datasets exist; do not read them");
  return bag_topic_action(cmd, args, &ListArgs::log, [](const ListArgs& a) { return list(a); });
}

}  // namespace locbench::cli
