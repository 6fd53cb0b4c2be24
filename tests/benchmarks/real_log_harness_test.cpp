// The real-log harness: dataset specs (catalog names or a user's files), and every real-data
// experiment run on a small log the test writes itself.
#include "pipelines/real_log_harness.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>

#include <fstream>
#include <map>

#include "core/errors.h"
#include "experiment_framework/experiment.h"
#include "pipelines/laser_correctors.h"
#include "pipelines/real_scan_pairs.h"
#include "tests/benchmarks/small_real_log.h"
#include "tests/test_data.h"

namespace locbench::experiments {
namespace {

using locbench::testing::ScratchDir;
using locbench::testing::write_small_real_log;

std::map<std::string, reports::MetricResult> by_name(const reports::ExperimentResults& r) {
  std::map<std::string, reports::MetricResult> m;
  for (const auto& x : r.results) m.emplace(x.name(), x);
  return m;
}

reports::ExperimentResults run_on(const std::string& experiment, nlohmann::json overrides) {
  const Experiment* e = find_experiment(experiment);
  EXPECT_NE(e, nullptr) << experiment;
  const nlohmann::json config = merge_config(e->default_config(), overrides);
  RunOptions o;
  o.data_root = "/nonexistent";  // nothing from the catalog is read
  return e->run(config, o);
}

// Odometry along x at 0.1 m/s from t = 0 to 10 s, scans at 1, 2, 3 and 5 s: a relation pairs two
// scans when both stamps have one (within 1 ms), it spans at most max_dt and the odometry covers
// it; the guess is the odometry's motion between the stamps.
TEST(RelationScanPairs, KeepRelationsWithTwoScansInsideTheOdometryUpToMaxPairs) {
  Log log;
  for (int t = 0; t <= 10; ++t) log.odometry.push_back({static_cast<double>(t), Pose2(0.1 * t, 0.0, 0.0), 0.1, 0.0});
  for (const double t : {1.0, 2.0, 3.0, 5.0}) {
    LaserReading r;
    r.scan.timestamp = t;
    log.laser.push_back(r);
  }
  log.relations = {{1.0, 2.0, {}},
                   {2.0, 3.0005, {}},
                   {3.0, 4.0, {}},  // no scan at 4 s
                   {1.0, 5.0, {}},  // 4 s > max_dt
                   {3.0, 5.0, {}}};
  const std::vector<RelationScanPair> all = relation_scan_pairs(log, 3.0);
  ASSERT_EQ(all.size(), 3u);
  EXPECT_EQ(all[0].relation, 0u);
  EXPECT_EQ(all[1].relation, 1u);
  EXPECT_EQ(all[2].relation, 4u);
  EXPECT_EQ(all[1].first, 1u);
  EXPECT_EQ(all[1].second, 2u);
  EXPECT_NEAR(all[2].odometry.x, 0.2, 1e-12);
  EXPECT_NEAR(all[2].odometry.y, 0.0, 1e-12);
  EXPECT_EQ(relation_scan_pairs(log, 3.0, 2).size(), 2u);
}

TEST(RealLogSpecs, TakeCatalogNamesAndUserFiles) {
  ScratchDir dir;
  const auto files = write_small_real_log(dir.path());
  const auto specs = real_log_specs(
      nlohmann::json::array(
          {"aces", {{"name", "mine"}, {"log", files.log.string()}, {"relations", files.relations.string()}}}),
      "x");
  ASSERT_EQ(specs.size(), 2u);
  EXPECT_TRUE(specs[0].from_catalog);
  EXPECT_EQ(specs[0].name, "aces");
  EXPECT_FALSE(specs[1].from_catalog);
  EXPECT_EQ(specs[1].relations, files.relations.string());
  EXPECT_EQ(real_log_names(specs), (std::vector<std::string>{"aces", "mine"}));
}

TEST(RealLogSpecs, RejectUnknownNamesKeysDuplicatesAndMissingFiles) {
  ScratchDir dir;
  const auto files = write_small_real_log(dir.path());
  const std::string log = files.log.string();
  EXPECT_THROW(real_log_specs({"no_such_dataset"}, "x"), UsageError);
  EXPECT_THROW(real_log_specs(nlohmann::json::array({{{"name", "a"}, {"log", log}, {"relation", "r"}}}), "x"),
               UsageError);
  EXPECT_THROW(
      real_log_specs(nlohmann::json::array({{{"name", "a"}, {"log", log}}, {{"name", "a"}, {"log", log}}}), "x"),
      UsageError);
  EXPECT_THROW(real_log_specs(nlohmann::json::array({{{"log", log}}}), "x"), UsageError);
  EXPECT_THROW(
      real_log_specs(nlohmann::json::array({{{"name", "a"}, {"log", (dir.path() / "absent.clf").string()}}}), "x"),
      InputError);
  EXPECT_THROW(
      real_log_specs(nlohmann::json::array(
                         {{{"name", "a"}, {"log", log}, {"relations", (dir.path() / "absent.relations").string()}}}),
                     "x"),
      InputError);
  EXPECT_THROW(real_log_specs(nlohmann::json::array({42}), "x"), UsageError);
}

TEST(RealLogSpecs, MissingCatalogDataIsSkippedWithTheReason) {
  const auto specs = real_log_specs({"intel"}, "x");
  const LoadedRealLog l = load_real_log(specs[0], "/nonexistent");
  EXPECT_EQ(l.status, "skipped");
  EXPECT_NE(l.reason.find("LOCBENCH_DATA"), std::string::npos);
}

TEST(RealLogSpecs, CliFlagsBecomeOneDatasetNamedAfterTheLog) {
  const auto o = real_log_cli_override("/a/b/my.clf.gz", "/a/my.relations", "");
  ASSERT_TRUE(o);
  EXPECT_EQ((*o)["datasets"][0]["name"], "my");
  EXPECT_EQ((*o)["datasets"][0]["log"], "/a/b/my.clf.gz");
  EXPECT_EQ((*o)["datasets"][0]["relations"], "/a/my.relations");
  EXPECT_FALSE((*o)["datasets"][0].contains("ground_truth"));
  EXPECT_FALSE(real_log_cli_override("", "", ""));
}

// An MRCLAM folder with robot 1 (odometry from t = 10 s), no landmark file of its own.
std::filesystem::path write_mrclam_folder(const std::filesystem::path& dir) {
  const auto folder = dir / "MRCLAM_Dataset9";
  std::filesystem::create_directories(folder);
  std::ofstream(folder / "Robot1_Odometry.dat") << "# h\n10 0.1 0\n11 0.1 0\n12 0 0\n";
  std::ofstream(folder / "Robot1_Groundtruth.dat") << "# h\n10 0 0 0\n12 0.2 0 0\n";
  std::ofstream(folder / "Robot1_Measurement.dat") << "# h\n";
  return folder;
}

TEST(RealLogSpecs, AnMrclamFolderWithARobotSuffixIsAUsersLog) {
  ScratchDir dir;
  const std::string log = write_mrclam_folder(dir.path()).string() + "#robot1";
  const auto specs = real_log_specs(nlohmann::json::array({{{"name", "m"}, {"log", log}}}), "x");
  const LoadedRealLog l = load_real_log(specs.at(0), "/nonexistent");
  EXPECT_EQ(l.status, "ok");
  EXPECT_EQ(l.log.odometry.size(), 3u);
  const std::string absent = (dir.path() / "MRCLAM_Dataset8").string() + "#robot1";
  EXPECT_THROW(real_log_specs(nlohmann::json::array({{{"name", "m"}, {"log", absent}}}), "x"), InputError);
}

TEST(RealLogSpecs, ACatalogLogIsReadOnceAndReadAgainWhenItsFilesChange) {
  ScratchDir dir;
  const auto folder = dir.path() / "mrclam" / "MRCLAM_Dataset6";
  std::filesystem::create_directories(folder);
  std::ofstream(folder / "Robot1_Odometry.dat") << "# h\n10 0.1 0\n11 0.1 0\n12 0 0\n";
  std::ofstream(folder / "Robot1_Groundtruth.dat") << "# h\n10 0 0 0\n12 0.2 0 0\n";
  std::ofstream(folder / "Robot1_Measurement.dat") << "# h\n";
  const auto specs = real_log_specs({"mrclam6_robot1"}, "x");
  const LoadedRealLog first = load_real_log(specs.at(0), dir.path());
  ASSERT_EQ(first.status, "ok") << first.reason;
  EXPECT_EQ(first.log.odometry.size(), 3u);
  const LoadedRealLog again = load_real_log(specs.at(0), dir.path());
  EXPECT_EQ(again.log.odometry.size(), 3u);
  EXPECT_EQ(again.dataset.checksum, first.dataset.checksum);

  std::filesystem::remove(folder / "Robot1_Odometry.dat");
  std::ofstream(folder / "Robot1_Odometry.dat") << "# h\n10 0.1 0\n11 0.1 0\n12 0 0\n13 0 0\n";
  std::filesystem::last_write_time(folder, std::filesystem::last_write_time(folder) + std::chrono::seconds(10));
  const LoadedRealLog changed = load_real_log(specs.at(0), dir.path());
  EXPECT_EQ(changed.log.odometry.size(), 4u);
}

TEST(RealLogSpecs, LandmarkFilesAreAttachedOnLoad) {
  ScratchDir dir;
  const std::string log = write_mrclam_folder(dir.path()).string() + "#robot1";
  std::ofstream(dir.file("map.txt")) << "# id x y\n6 1 2\n7 3 4 0.01 0.01\n";
  std::ofstream(dir.file("obs.txt")) << "10.5 6 1.5 0.25\n11 7 2 -0.5\n";
  const auto specs = real_log_specs(nlohmann::json::array({{{"name", "m"},
                                                            {"log", log},
                                                            {"landmark_map", dir.file("map.txt").string()},
                                                            {"landmark_observations", dir.file("obs.txt").string()}}}),
                                    "x");
  EXPECT_EQ(specs.at(0).landmark_map, dir.file("map.txt").string());
  const LoadedRealLog l = load_real_log(specs.at(0), "/nonexistent");
  ASSERT_EQ(l.log.landmark_map.size(), 2u);
  ASSERT_EQ(l.log.landmarks.size(), 2u);
  EXPECT_EQ(l.log.landmarks[1].subject, 7);
}

TEST(RealLogSpecs, MissingOrMalformedLandmarkFilesAreInputErrorsNamingTheFile) {
  ScratchDir dir;
  const std::string log = write_mrclam_folder(dir.path()).string();
  std::ofstream(dir.file("map.txt")) << "6 1 2\n";
  std::ofstream(dir.file("obs.txt")) << "10.5 6 1.5 0.25\n11 8 2 -0.5\n";  // 8 is not in the map
  auto spec = [&](const std::string& map, const std::string& obs) {
    nlohmann::json item = {{"name", "m"}, {"log", log}, {"landmark_map", map}};
    if (!obs.empty()) item["landmark_observations"] = obs;
    return nlohmann::json::array({item});
  };
  try {
    real_log_specs(spec(dir.file("absent.txt").string(), ""), "x");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("absent.txt"), std::string::npos) << e.what();
  }
  const auto specs = real_log_specs(spec(dir.file("map.txt").string(), dir.file("obs.txt").string()), "x");
  try {
    load_real_log(specs.at(0), "/nonexistent");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 2u);
    EXPECT_NE(e.file().find("obs.txt"), std::string::npos) << e.what();
  }
  EXPECT_THROW(real_log_specs(nlohmann::json::array({{{"name", "aces"}, {"landmark_map", "m.txt"}}}), "x"), UsageError);
}

TEST(RealLogSpecs, CliLandmarkFlagsAndAnMrclamRobotBecomeOneDataset) {
  const auto o = real_log_cli_override("/d/MRCLAM_Dataset6#robot2", "", "", "/d/map.txt", "/d/obs.txt");
  ASSERT_TRUE(o);
  EXPECT_EQ((*o)["datasets"][0]["name"], "MRCLAM_Dataset6_robot2");
  EXPECT_EQ((*o)["datasets"][0]["log"], "/d/MRCLAM_Dataset6#robot2");
  EXPECT_EQ((*o)["datasets"][0]["landmark_map"], "/d/map.txt");
  EXPECT_EQ((*o)["datasets"][0]["landmark_observations"], "/d/obs.txt");
  EXPECT_FALSE((*o)["datasets"][0].contains("relations"));
}

TEST(RealLogExperiments, LaserRealLogsCorrectsAUsersLog) {
  ScratchDir dir;
  const auto files = write_small_real_log(dir.path());
  const auto r =
      run_on("laser/real_logs",
             {{"datasets", {{{"name", "mine"}, {"log", files.log.string()}, {"relations", files.relations.string()}}}},
              {"matchers", {"eap"}},
              {"correctors", {"pl_icp", "eap_iterated_pl", "icp_point_to_point", "eap_ch6_inverse_variance"}}});
  ASSERT_TRUE(r.cases.empty()) << r.cases.front().reason;
  ASSERT_EQ(r.datasets.size(), 1u);
  EXPECT_EQ(r.datasets[0].name, "mine");
  const auto m = by_name(r);
  EXPECT_EQ(m.at("odometry_raw/mine/rpe_translation").summary.n, files.relation_count);
  // Odometry is 3% long and 1.5° over-turned per step: 3.6 mm and 1.5° per relation.
  EXPECT_NEAR(m.at("odometry_raw/mine/rpe_rotation").summary.mean, deg(1.5), deg(0.01));
  for (const char* method : {"pl_icp", "eap_iterated_pl"}) {
    EXPECT_LT(m.at(std::string(method) + "/mine/rpe_rotation").summary.mean, deg(0.2)) << method;
    EXPECT_LT(m.at(std::string(method) + "/mine/rpe_translation").summary.mean, 0.01) << method;
  }
  // Point-to-point ICP pairs beams, not surface points: biased, but still half odometry's error.
  EXPECT_LT(m.at("icp_point_to_point/mine/rpe_rotation").summary.mean, deg(0.75));
  // One chapter-6 pass with inverse-variance heading weights fixes most of the 1.5°.
  EXPECT_LT(m.at("eap_ch6_inverse_variance/mine/rpe_rotation").summary.mean, deg(0.5));
  // Paired differences against odometry, relation by relation: their mean is the difference
  // of the means.
  const auto& d = m.at("pl_icp/mine/rpe_rotation_minus_odometry");
  EXPECT_EQ(d.summary.n, files.relation_count);
  EXPECT_NEAR(d.summary.mean,
              m.at("pl_icp/mine/rpe_rotation").summary.mean - m.at("odometry_raw/mine/rpe_rotation").summary.mean,
              1e-12);
  EXPECT_LT(d.summary.ci95_high, 0.0);
  // The 3 worst relations of eap_ch6_ls drawn before and after, in the first robot frame.
  // First each method's error distribution (translation, rotation): one CDF series per method,
  // every relation's error (fewer than 200, so none thinned out).
  ASSERT_EQ(r.plots.size(), 8u);
  for (int k = 0; k < 2; ++k) {
    const auto& c = r.plots[static_cast<std::size_t>(k)];
    EXPECT_EQ(c.kind, "cdf");
    ASSERT_FALSE(c.series.empty());
    EXPECT_EQ(c.series[0].name, "odometry_raw");
    EXPECT_EQ(c.series[0].y.size(), files.relation_count);
    EXPECT_TRUE(std::is_sorted(c.series[0].y.begin(), c.series[0].y.end()));
  }
  std::vector<reports::Plot> pairs(r.plots.begin() + 2, r.plots.end());
  for (const auto& p : pairs) {
    EXPECT_EQ(p.kind, "scan_pair");
    ASSERT_GE(p.series.size(), 4u);
    EXPECT_EQ(p.series[0].name, "first scan");
    EXPECT_EQ(p.series[0].x.size(), 181u);    // every beam of the room hits a wall
    EXPECT_EQ(p.series[1].x.size() % 2, 0u);  // lines as point pairs
  }
  EXPECT_NE(pairs[0].title.find("before"), std::string::npos);
  EXPECT_NE(pairs[1].title.find("after"), std::string::npos);
}

TEST(RealLogExperiments, LaserRealLogsMakesItsCorrectorsOncePerRunForAllLogsAndThreads) {
  ScratchDir dir;
  const auto files = write_small_real_log(dir.path());
  const nlohmann::json log = {{"log", files.log.string()}, {"relations", files.relations.string()}};
  nlohmann::json first = log, second = log;
  first["name"] = "first";
  second["name"] = "second";
  const Experiment* e = find_experiment("laser/real_logs");
  ASSERT_NE(e, nullptr);
  const nlohmann::json config = merge_config(
      e->default_config(), {{"datasets", {first, second}}, {"matchers", {"eap"}}, {"correctors", {"pl_icp"}}});
  RunOptions o;
  o.data_root = "/nonexistent";
  o.threads = 2;
  const std::size_t before = make_correctors_calls();
  const auto r = e->run(config, o);
  EXPECT_EQ(make_correctors_calls() - before, 1u);
  ASSERT_TRUE(r.cases.empty()) << r.cases.front().reason;
  EXPECT_EQ(by_name(r).at("pl_icp/second/rpe_rotation").summary.n, files.relation_count);
}

// global/real_logs places its map on the scan-matched path: on the small log, whose odometry
// over-turns 1.5° per step (34° over the 23 steps), that path ends far from the odometry; with
// map_poses = "odometry" the map and the reference are the odometry's, as before.
TEST(RealLogExperiments, GlobalRealLogsBuildsItsMapOnTheScanMatchedPath) {
  ScratchDir dir;
  const auto files = write_small_real_log(dir.path());
  nlohmann::json o = {{"datasets", {{{"name", "mine"}, {"log", files.log.string()}}}},
                      {"methods", {"ekf_eap"}},
                      {"window_s", 11.0},
                      {"map_every", 1}};
  const auto matched = run_on("global/real_logs", o);
  ASSERT_TRUE(matched.cases.empty()) << matched.cases.front().reason;
  const std::string& note = matched.notes.front();
  EXPECT_NE(note.find("placed by scan_matched"), std::string::npos) << note;
  // Truth after 23 steps of (0.12 m, 4°) vs odometry's (0.1236 m, 5.5°): 0.71 m apart.
  const auto at = note.find("(ends ");
  ASSERT_NE(at, std::string::npos) << note;
  EXPECT_GT(std::stod(note.substr(at + 6)), 0.3) << note;
  o["map_poses"] = "odometry";
  const auto plain = run_on("global/real_logs", o);
  EXPECT_NE(plain.notes.front().find("placed by odometry"), std::string::npos) << plain.notes.front();
  EXPECT_EQ(plain.notes.front().find("(ends "), std::string::npos);
  o["map_poses"] = "truth";
  EXPECT_THROW(run_on("global/real_logs", o), UsageError);
}

TEST(RealLogExperiments, OdometryAndNoiseRealLogsReadAUsersLog) {
  ScratchDir dir;
  const auto files = write_small_real_log(dir.path());
  const nlohmann::json datasets = {
      {"datasets", {{{"name", "mine"}, {"log", files.log.string()}, {"relations", files.relations.string()}}}}};
  const auto odo = by_name(run_on("odometry/real_logs", datasets));
  EXPECT_EQ(odo.at("odometry_raw/mine/rpe_rotation").summary.n, files.relation_count);
  EXPECT_NEAR(odo.at("odometry_raw/mine/rpe_rotation").summary.mean, deg(1.5), deg(0.01));
  const auto noise = by_name(run_on("noise/real_logs", datasets));
  EXPECT_EQ(noise.at("fixed_q/mine/relation_nees").summary.n, files.relation_count);
}

TEST(RealLogExperiments, AMalformedRelationsFileIsAnInputError) {
  ScratchDir dir;
  const auto files = write_small_real_log(dir.path());
  std::ofstream(files.relations, std::ios::app) << "100.0 100.5 oops\n";
  EXPECT_THROW(run_on("odometry/real_logs",
                      {{"datasets",
                        {{{"name", "mine"}, {"log", files.log.string()}, {"relations", files.relations.string()}}}}}),
               InputError);
}

}  // namespace
}  // namespace locbench::experiments
