// finish_report, the one tail of every verb's report: provenance stamped, schema checked,
// summary printed, file written atomically, "wrote PATH" said.
#include "reports/finish_report.h"

#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>

#include "core/errors.h"
#include "reports/provenance.h"
#include "reports/report_json.h"
#include "reports/schema_validation.h"
#include "reports/summary_table.h"
#include "tests/reports/sample_report.h"
#include "tests/test_data.h"

namespace locbench::reports {
namespace {

std::size_t files_in(const std::filesystem::path& folder) {
  std::size_t n = 0;
  for (const auto& e : std::filesystem::directory_iterator(folder)) n += e.is_regular_file();
  return n;
}

std::string logic_error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::logic_error& e) {
    return e.what();
  }
  return "";
}

// The smallest document diagnosis.schema.json accepts: a histogram diagnosis with nothing found.
nlohmann::json empty_diagnosis() {
  return {{"schema", "locbench.diagnosis/1"},
          {"log", "residuals.json"},
          {"reference", "histogram"},
          {"nominal_model", {{"residual", "heading"}, {"distribution", "normal"}}},
          {"false_alarm", 0.01},
          {"residual_tests", nlohmann::json::array()},
          {"causes", nlohmann::json::array()},
          {"detected", nlohmann::json::array()},
          {"unexplained", nlohmann::json::array()},
          {"unconfirmed", nlohmann::json::array()},
          {"confounded", nlohmann::json::array()},
          {"not_testable", nlohmann::json::array()},
          {"gain", nlohmann::json::array()},
          {"noise_floor", {{"window_s", 1.0}, {"sigma_x_m", 0.0}, {"sigma_y_m", 0.0}, {"sigma_theta_rad", 0.0}}},
          {"verdict", "consistent with the nominal model"}};
}

TEST(FinishReport, StampsTheProvenanceAndWritesAValidReportAtomically) {
  testing::ScratchDir dir;
  Report report = testing::sample_report();
  std::ostringstream out, log;
  const auto path = dir.file("out/odometry/sim_corridor.json");
  ReportTail tail("odometry/sim_corridor", "locbench run odometry", path);
  tail.threads = 3;
  finish_report(report, tail, out, log);
  EXPECT_EQ(log.str(), "wrote " + path.string() + "\n");
  EXPECT_EQ(out.str(), "");  // no summary unless asked
  EXPECT_EQ(testing::file_contents(path), to_json(report).dump(2) + "\n");
  const Report back = read_report(path);
  EXPECT_EQ(back.provenance.command_line, "locbench run odometry");
  EXPECT_EQ(back.provenance.threads, 3);
  EXPECT_EQ(back.provenance.shards, std::nullopt);
  EXPECT_EQ(back.provenance.git_revision, current_provenance("").git_revision);  // this build's, not the sample's
  EXPECT_TRUE(validate_report_json(to_json(back)).empty());
  EXPECT_EQ(files_in(path.parent_path()), 1u);  // no temporary file left beside it
}

TEST(FinishReport, StampsOneRunIdPerInvocationIntoEveryReport) {
  testing::ScratchDir dir;
  Report a = testing::sample_report(), b = testing::sample_report();
  std::ostringstream out, log;
  finish_report(a, ReportTail("a", "locbench run", dir.file("a.json")), out, log);
  finish_report(b, ReportTail("b", "locbench run", dir.file("b.json")), out, log);
  EXPECT_FALSE(read_report(dir.file("a.json")).provenance.run_id.empty());
  EXPECT_EQ(read_report(dir.file("a.json")).provenance.run_id, read_report(dir.file("b.json")).provenance.run_id);
  EXPECT_EQ(read_report(dir.file("a.json")).provenance.run_id, invocation_run_id());
}

TEST(FinishReport, PrintsTheSummaryThenEachResultNoteThenEachNoteWhenAsked) {
  Report report = testing::sample_report();
  std::ostringstream out, log;
  ReportTail tail("calibrate", "locbench calibrate", "");
  tail.print_summary = true;
  finish_report(report, tail, out, log);
  EXPECT_EQ(out.str(), summary_table({report}) +
                           "umbmark_improved/sim_trilobot/E_o: only E_o/E_b is determined by the square\n"
                           "a finding in plain words\n");
  EXPECT_EQ(log.str(), "");  // no path: nothing written, nothing said
}

TEST(FinishReport, SaysWhatWasWrittenInParentheses) {
  testing::ScratchDir dir;
  Report report = testing::sample_report();
  std::ostringstream out, log;
  ReportTail tail("merge of odometry/sim_corridor", "locbench merge", dir.file("r.json"));
  tail.threads = 2;
  tail.shards = 4;
  tail.wrote_detail = "4 shards";
  finish_report(report, tail, out, log);
  EXPECT_EQ(log.str(), "wrote " + dir.file("r.json").string() + " (4 shards)\n");
  EXPECT_EQ(read_report(dir.file("r.json")).provenance.shards, 4);
}

TEST(FinishReport, AReportViolatingTheSchemaIsABugNamingTheProducerAndReplacesNothing) {
  testing::ScratchDir dir;
  const auto path = dir.file("r.json");
  std::ofstream(path) << "previous report";
  Report report = testing::sample_report();
  report.body.results.front().better = "sideways";  // not in the schema's enum
  std::ostringstream out, log;
  ReportTail tail("calibrate", "locbench calibrate", path);
  tail.print_summary = true;
  const std::string e = logic_error_of([&] { finish_report(report, tail, out, log); });
  EXPECT_EQ(e.rfind("calibrate produced a report that violates reports/report.schema.json: ", 0), 0u) << e;
  EXPECT_EQ(testing::file_contents(path), "previous report");
  EXPECT_EQ(out.str(), "");  // nothing printed for a report that is not written
  EXPECT_EQ(log.str(), "");
}

TEST(FinishReport, AFolderInPlaceOfTheFileIsAnInputErrorNamingIt) {
  testing::ScratchDir dir;
  std::filesystem::create_directories(dir.file("taken"));
  Report report = testing::sample_report();
  std::ostringstream out, log;
  try {
    finish_report(report, ReportTail("match", "locbench match", dir.file("taken")), out, log);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(dir.file("taken").string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("is a folder"), std::string::npos) << e.what();
  }
  EXPECT_EQ(log.str(), "");
}

TEST(FinishReport, WritesAShardReportWithItsTaskCount) {
  testing::ScratchDir dir;
  ShardReport shard;
  shard.experiment = "odometry/sim_corridor";
  shard.description = "dead reckoning on a simulated corridor";
  shard.index = 2;
  shard.count = 2;
  shard.tasks = 3;
  shard.records = {{1, {{"error", 0.25}}}};
  const auto path = dir.file("odometry/sim_corridor.shard-2-of-2.json");
  std::ostringstream log;
  ReportTail tail("odometry/sim_corridor", "locbench run --shard 2/2", path);
  tail.threads = 1;
  tail.wrote_detail = "1 of 3 tasks";
  finish_report(shard, tail, log);
  EXPECT_EQ(log.str(), "wrote " + path.string() + " (1 of 3 tasks)\n");
  const ShardReport back = read_shard_report(path);
  EXPECT_EQ(back.provenance.command_line, "locbench run --shard 2/2");
  EXPECT_EQ(back.records.size(), 1u);
  EXPECT_EQ(back.records.front().record.at("error"), 0.25);
}

TEST(FinishReport, WritesADiagnosisWithItsProvenance) {
  testing::ScratchDir dir;
  nlohmann::json d = empty_diagnosis();
  std::ostringstream log;
  finish_report(d, ReportTail("diagnose", "locbench diagnose residuals.json", dir.file("d.json")), log);
  EXPECT_EQ(log.str(), "wrote " + dir.file("d.json").string() + "\n");
  const nlohmann::json back = nlohmann::json::parse(testing::file_contents(dir.file("d.json")));
  EXPECT_EQ(back.at("provenance").at("command_line"), "locbench diagnose residuals.json");
  EXPECT_EQ(back.at("verdict"), "consistent with the nominal model");
  EXPECT_TRUE(validate_diagnosis_json(back).empty());
}

TEST(FinishReport, ADiagnosisViolatingItsSchemaIsABugAndNothingIsWritten) {
  testing::ScratchDir dir;
  nlohmann::json d = empty_diagnosis();
  d.erase("verdict");
  std::ostringstream log;
  const std::string e =
      logic_error_of([&] { finish_report(d, ReportTail("diagnose", "locbench diagnose", dir.file("d.json")), log); });
  EXPECT_EQ(e.rfind("diagnose produced a report that violates reports/diagnosis.schema.json: ", 0), 0u) << e;
  EXPECT_FALSE(std::filesystem::exists(dir.file("d.json")));
}

}  // namespace
}  // namespace locbench::reports
