#pragma once
// Registration of an experiment: one line in the experiment's own file, beside its class, the way
// Google Benchmark's BENCHMARK() works:
//
//   namespace locbench::experiments::odometry_sim_corridor {
//   const ExperimentInfo kInfo{.name = "odometry/sim_corridor", .description = "…"};
//   class OdometrySimCorridor final : public MonteCarloExperiment<Options, Setup> { … };
//   const Registration<OdometrySimCorridor> odometry_sim_corridor_registration(kInfo);
//   }  // namespace locbench::experiments::odometry_sim_corridor     (or …("constructor arg"))
//
// The name, description and reading notes are data (ExperimentInfo), stated once, at the top of
// the file; the class needs no constructor (Registration gives it the info). The file's own types
// and the registrar live in a namespace named after the file (<topic>_<name>), not an anonymous
// one, so that files batched into one unity-build unit never define the same name twice. The
// registrar runs while the program loads and stores a factory; no experiment is constructed then.
// all_experiments() (experiment.h) makes each one once, on first use, sorted by name, so the order
// never depends on the link order. The experiments are compiled into an OBJECT library
// (../CMakeLists.txt), which puts every registrar into the program: from a static library the
// linker would drop the files nothing refers to.
#include <functional>
#include <memory>
#include <vector>

#include "experiment_framework/experiment.h"

namespace locbench::experiments {

using ExperimentFactory = std::function<std::unique_ptr<Experiment>()>;

// Adds a factory to the registry; called by Registration while the program loads.
void register_experiment(ExperimentFactory make);

// One experiment from each factory, sorted by name (what all_experiments() holds);
// std::logic_error naming the experiment when two have the same name.
std::vector<std::unique_ptr<Experiment>> make_sorted(const std::vector<ExperimentFactory>& factories);

template <typename E>
class Registration {
 public:
  // E is default-constructed and given `info`.
  explicit Registration(ExperimentInfo info) {
    register_experiment([info] {
      auto e = std::make_unique<E>();
      e->info_ = info;
      return e;
    });
  }
  // The arguments are copied into the factory and given to E's constructor, which states the info.
  template <typename... Args>
  explicit Registration(Args... args) {
    register_experiment([args...] { return std::make_unique<E>(args...); });
  }
};

}  // namespace locbench::experiments
