// diagnosis/real_logs on a user's log: the log's motion data are built once, for the diagnosis,
// the scale checks and the plots alike.
#include <gtest/gtest.h>

#include "algorithms/diagnosis/motion_windows.h"
#include "datasets/io/carmen_writer.h"
#include "datasets/io/tum_writer.h"
#include "datasets/sim/presets.h"
#include "datasets/sim/simulator.h"
#include "experiment_framework/experiment.h"
#include "tests/test_data.h"

namespace locbench::experiments {
namespace {

using locbench::testing::ScratchDir;

TEST(DiagnosisRealLogs, BuildsEachLogsMotionDataOnce) {
  ScratchDir dir;
  const sim::SimulationResult corridor = sim::simulate(sim::preset("corridor"), 7);
  io::write_carmen_log(corridor.log, dir.file("corridor.clf"));
  io::write_tum(sim::true_trajectory(corridor), dir.file("corridor.tum"));
  const Experiment* e = find_experiment("diagnosis/real_logs");
  ASSERT_NE(e, nullptr);
  const nlohmann::json config =
      merge_config(e->default_config(), {{"datasets",
                                          {{{"name", "corridor"},
                                            {"log", dir.file("corridor.clf").string()},
                                            {"ground_truth", dir.file("corridor.tum").string()}}}}});
  RunOptions o;
  o.data_root = "/nonexistent";
  const std::size_t before = diagnosis::build_motion_data_calls();
  const auto r = e->run(config, o);
  EXPECT_EQ(diagnosis::build_motion_data_calls() - before, 1u);
  ASSERT_TRUE(r.cases.empty()) << r.cases.front().reason;
  EXPECT_FALSE(r.results.empty());
  EXPECT_FALSE(r.plots.empty());
}

}  // namespace
}  // namespace locbench::experiments
