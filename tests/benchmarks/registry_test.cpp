#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "experiment_framework/experiment.h"
#include "experiment_framework/registry.h"

namespace locbench::experiments {
namespace {

std::vector<std::string> registered_names() {
  std::vector<std::string> names;
  for (const auto& e : all_experiments()) names.push_back(e->name());
  return names;
}

// "topic/name" of every benchmarks/experiments/<topic>/<name>.cpp.
std::set<std::string> experiment_files() {
  const std::filesystem::path root = std::filesystem::path(LOCBENCH_SOURCE_DIR) / "benchmarks" / "experiments";
  std::set<std::string> names;
  for (const auto& topic : std::filesystem::directory_iterator(root)) {
    const std::string t = topic.path().filename().string();
    if (!topic.is_directory()) continue;
    for (const auto& f : std::filesystem::directory_iterator(topic.path())) {
      if (f.path().extension() == ".cpp") names.insert(t + "/" + f.path().stem().string());
    }
  }
  return names;
}

TEST(Registry, EveryExperimentHasAUniqueNameAndAValidDefaultConfig) {
  std::set<std::string> names;
  for (const auto& e : all_experiments()) {
    EXPECT_TRUE(names.insert(e->name()).second) << e->name();
    EXPECT_TRUE(e->default_config().is_object()) << e->name();
    EXPECT_EQ(find_experiment(e->name()), e.get());
  }
  EXPECT_EQ(find_experiment("no/such"), nullptr);
}

// The linker keeps every registrar (the experiments are an OBJECT library) and each file
// registers the experiment it is named after: the registry is exactly the files.
TEST(Registry, HoldsOneExperimentPerFileNamedAsTheFileIs) {
  const std::set<std::string> files = experiment_files();
  const std::vector<std::string> names = registered_names();
  EXPECT_EQ(std::set<std::string>(names.begin(), names.end()), files);
  EXPECT_EQ(names.size(), files.size());
  EXPECT_GE(files.size(), 28u);  // the suite as it stood when the registry was written
}

// An experiment that only has a name, for the registry's own logic.
class Named final : public Experiment {
 public:
  explicit Named(std::string name) : Experiment({.name = std::move(name), .description = "test"}) {}
  nlohmann::json default_config() const override { return nlohmann::json::object(); }
  reports::ExperimentResults run(const nlohmann::json&, const RunOptions&) const override { return {}; }
};

ExperimentFactory named(const std::string& name) {
  return [name] { return std::make_unique<Named>(name); };
}

// The order is by name, not by the order the program happened to run the registrars in.
TEST(Registry, SortsTheExperimentsByNameWhateverOrderTheyRegisteredIn) {
  const auto v = make_sorted({named("slip/b"), named("odometry/z"), named("calibration/a")});
  ASSERT_EQ(v.size(), 3u);
  EXPECT_EQ(v[0]->name(), "calibration/a");
  EXPECT_EQ(v[1]->name(), "odometry/z");
  EXPECT_EQ(v[2]->name(), "slip/b");
  const std::vector<std::string> names = registered_names();
  EXPECT_TRUE(std::is_sorted(names.begin(), names.end()));
}

TEST(Registry, RefusesTwoExperimentsOfTheSameName) {
  try {
    make_sorted({named("laser/x"), named("odometry/y"), named("laser/x")});
    FAIL() << "no error";
  } catch (const std::logic_error& e) {
    EXPECT_NE(std::string(e.what()).find("\"laser/x\""), std::string::npos) << e.what();
  }
}

TEST(Registry, LeavesOnlyTheSlowSimulationsAndTheGlobalRealLogsOutOfTheDefaultSuite) {
  std::vector<std::string> outside;
  for (const auto& e : all_experiments()) {
    if (!e->in_default_suite()) outside.push_back(e->name());
  }
  EXPECT_EQ(outside,
            (std::vector<std::string>{"diagnosis/false_alarms", "diagnosis/power", "global/real_logs", "global/sim"}));
}

}  // namespace
}  // namespace locbench::experiments
