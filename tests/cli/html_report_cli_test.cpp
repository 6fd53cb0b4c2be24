// `locbench report`: the page a person reads, rendered in headless Chromium the way they would
// open it — charts drawn (inline SVG with plotted paths), no console errors, a screenshot kept in
// the build folder (LOCBENCH_ARTIFACT_DIR) as the test's artifact.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>

#include "tests/benchmarks/small_real_log.h"
#include "tests/cli/cli_helpers.h"
#include "tests/test_data.h"

namespace locbench {
namespace {

using testing::Outcome;
using testing::run_locbench;
using testing::run_shell;

struct Rendered {
  int exit_code = -1;
  std::string dom;
  std::string log;  // Chromium's stderr log
};

// Headless Chromium with a fresh profile and no network features; --dump-dom, or a screenshot
// when `screenshot` is set.
Rendered render(const std::filesystem::path& html, const std::filesystem::path& profile,
                const std::string& screenshot = "") {
  const std::string flags =
      "--headless --no-sandbox --disable-gpu --disable-quic --no-first-run "
      "--disable-background-networking --disable-component-update --disable-sync "
      "--enable-logging=stderr --v=0 --user-data-dir=" +
      profile.string();
  const auto dom = profile.string() + ".dom";
  const auto log = profile.string() + ".log";
  const std::string what =
      screenshot.empty() ? "--dump-dom" : "--screenshot=" + screenshot + " --window-size=1280,4000";
  Rendered r;
  r.exit_code = run_shell("chromium " + flags + " " + what + " file://" + std::filesystem::absolute(html).string() +
                          " > " + dom + " 2> " + log)
                    .exit_code;
  r.dom = testing::file_contents(dom);
  r.log = testing::file_contents(log);
  return r;
}

// What the page itself printed: Chromium logs each console message and each uncaught script
// exception of the page as a "CONSOLE" line. Chromium's own errors (D-Bus without a session bus,
// GPU or viz messages when the machine is loaded) are not the page's and are not counted: a
// loaded CI machine once added one to the single error the page below logs.
std::vector<std::string> problems(const std::string& log) {
  std::vector<std::string> out;
  std::istringstream in(log);
  for (std::string line; std::getline(in, line);) {
    if (line.find("CONSOLE") != std::string::npos) out.push_back(line);
  }
  return out;
}

// The most `command` letters ('L' line segments, 'M' moves) in one `d` attribute of `svg`.
std::size_t most_in_one_path(const std::string& svg, char command) {
  std::size_t best = 0;
  for (std::size_t at = svg.find(" d="); at != std::string::npos; at = svg.find(" d=", at + 1)) {
    const char quote = svg[at + 3];
    const std::size_t end = svg.find(quote, at + 4);
    const std::string d = svg.substr(at + 4, end - at - 4);
    best = std::max<std::size_t>(best, static_cast<std::size_t>(std::count(d.begin(), d.end(), command)));
  }
  return best;
}

// The most line segments in one SVG path of `svg` (a plotted series has many; a frame few).
std::size_t longest_path(const std::string& svg) { return most_in_one_path(svg, 'L'); }

std::size_t count_of(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

class HtmlReport : public ::testing::Test {
 protected:
  void SetUp() override {
    if (run_shell("command -v chromium").exit_code != 0) {
      GTEST_SKIP() << "chromium not installed (scripts/setup.sh installs it)";
    }
  }
  // `locbench report` of the folder `reports` into `html`, and the page rendered; an exception
  // (a failed test) when either exits non-zero.
  Rendered report_and_render(const std::string& reports, const std::filesystem::path& html) {
    const Outcome o = run_locbench("report " + reports + " -o " + html.string());
    if (o.exit_code != 0) throw std::runtime_error("locbench report failed: " + o.output);
    Rendered r = render(html, dir.path() / "profile");
    if (r.exit_code != 0) throw std::runtime_error("chromium failed: " + r.log);
    return r;
  }

  testing::ScratchDir dir;
};

TEST_F(HtmlReport, RendersInChromiumWithItsChartsTablesAndNoConsoleErrors) {
  const std::string reports = (dir.path() / "reports").string();
  ASSERT_EQ(run_locbench("run odometry/sim_corridor noise/tables_4_1_4_2 --runs 5 --out " + reports).exit_code, 0);
  const std::filesystem::path artifacts(LOCBENCH_ARTIFACT_DIR);
  std::filesystem::create_directories(artifacts);
  const auto html = artifacts / "report.html";
  const Rendered r = report_and_render(reports, html);
  const std::string page = testing::file_contents(html);
  EXPECT_EQ(page.find("<script"), std::string::npos);
  EXPECT_EQ(std::regex_search(page, std::regex(R"((src|href)="?https?:)")), false);

  // Every chart figure holds an SVG with plotted paths: 2 + 2 plots, and histograms of the
  // final errors (5 runs each). (std::regex would recurse too deep on whole SVGs.)
  int charts = 0;
  for (std::size_t at = r.dom.find("<figure class=\"chart\""); at != std::string::npos;
       at = r.dom.find("<figure class=\"chart\"", at + 1)) {
    ++charts;
    const std::string f = r.dom.substr(at, r.dom.find("</figure>", at) - at);
    EXPECT_NE(f.find("<svg"), std::string::npos) << f.substr(0, 300);
    if (f.find("data-kind=\"histogram\"") != std::string::npos) {
      // Filled boxes: one legend swatch per method plus the bins with counts.
      EXPECT_GE(count_of(f, "<polygon"), 8u) << f.substr(0, 300);
    } else {
      EXPECT_GE(longest_path(f), 10u) << f.substr(0, 300);
    }
  }
  EXPECT_GE(charts, 6) << r.dom.substr(0, 500);
  EXPECT_NE(r.dom.find("data-kind=\"trajectory\""), std::string::npos);
  EXPECT_NE(r.dom.find("data-kind=\"error_vs_distance\""), std::string::npos);
  EXPECT_NE(r.dom.find("data-kind=\"histogram\""), std::string::npos);
  EXPECT_NE(r.dom.find("Published vs ours: thesis Tables 4.1/4.2"), std::string::npos);
  EXPECT_NE(r.dom.find("mean ± 95% interval"), std::string::npos);
  EXPECT_NE(r.dom.find("<h3>Findings</h3>"), std::string::npos);
  const auto found = problems(r.log);
  EXPECT_TRUE(found.empty()) << found.front();

  const auto shot = artifacts / "report_screenshot.png";
  std::filesystem::remove(shot);
  const Rendered s = render(html, dir.path() / "profile2", shot.string());
  ASSERT_EQ(s.exit_code, 0) << s.log;
  ASSERT_TRUE(std::filesystem::exists(shot));
  EXPECT_GT(std::filesystem::file_size(shot), 50'000u);  // a page of tables and charts, not blank
}

// Separate sub-paths ("M" moves) in the `d` attribute of `svg` that has the most.
std::size_t most_moves(const std::string& svg) { return most_in_one_path(svg, 'M'); }

// laser/real_logs on a user's log (written here): its worst relations drawn as scan pairs —
// both scans as points, the first scan's lines and the matches as separate segments — before
// (odometry) and after (corrections), under their own heading.
TEST_F(HtmlReport, DrawsTheWorstRelationsOfAUsersLogAsScanPairs) {
  const auto files = testing::write_small_real_log(dir.path());
  const std::string reports = (dir.path() / "reports").string();
  const Outcome run =
      run_locbench("run laser/real_logs --log " + files.log.string() + " --relations " + files.relations.string() +
                   " --set 'matchers=[\"eap\"]' --set draw_worst=2 --out " + reports);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto html = dir.file("relations.html");
  const Rendered r = report_and_render(reports, html);
  EXPECT_NE(r.dom.find("Scan pairs drawn: both scans, lines and matches, before and after"), std::string::npos);
  int pairs = 0;
  for (std::size_t at = r.dom.find("data-kind=\"scan_pair\""); at != std::string::npos;
       at = r.dom.find("data-kind=\"scan_pair\"", at + 1)) {
    ++pairs;
    const std::string f = r.dom.substr(at, r.dom.find("</figure>", at) - at);
    // Two scans of 181 beams each, drawn as point markers (gnuplot's pt 7, gpPt6).
    EXPECT_GE(count_of(f, "gpPt6"), 200u) << f.substr(0, 300);
    // The room's walls and pillar as lines of the first scan, and the matches: many separate
    // segments, not one polyline.
    EXPECT_GE(most_moves(f), 5u) << f.substr(0, 300);
    EXPECT_NE(f.find("first-scan lines"), std::string::npos);
  }
  EXPECT_EQ(pairs, 4);  // 2 relations × (before, after)
  EXPECT_NE(r.dom.find("before: odometry"), std::string::npos);
  EXPECT_NE(r.dom.find("after: eap_ch6_ls"), std::string::npos);
  const auto found = problems(r.log);
  EXPECT_TRUE(found.empty()) << found.front();
}

// The page opens on its findings: published tables with a verdict computed from their numbers
// (normality Table 3.1 recomputed from the same histogram; the quantization σ, where the thesis's
// 5.00 mm is not the L2 optimum), then each diagnosed log's kept causes — before the index of
// experiments. The diagnosed log (a simulated uncalibrated UMBmark run, its TRUEPOS the
// reference) gets its residual-against-covariate charts, its time-offset profile and the error
// CDFs of the nominal and the diagnosed model, all drawn.
TEST_F(HtmlReport, OpensOnTheFindingsAndDrawsTheDiagnosisCharts) {
  const auto log = dir.file("umbmark.clf");
  ASSERT_EQ(run_locbench("simulate umbmark_trilobot --seed 7 -o " + log.string()).exit_code, 0);
  const std::string reports = (dir.path() / "reports").string();
  const Outcome run = run_locbench("run diagnosis/real_logs --log " + log.string() + " --out " + reports);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const Outcome tables = run_locbench("run slip/normality_table_3_1 noise/quantization_sigma --out " + reports);
  ASSERT_EQ(tables.exit_code, 0) << tables.output;
  const auto html = dir.file("findings.html");
  const Rendered r = report_and_render(reports, html);
  const std::size_t findings = r.dom.find("<section id=\"findings\">");
  const std::size_t index = r.dom.find("<table class=\"overview\">");
  ASSERT_NE(findings, std::string::npos) << r.dom.substr(0, 800);
  ASSERT_NE(index, std::string::npos);
  EXPECT_LT(findings, index);  // findings first
  EXPECT_EQ(r.dom.find("<section", 0), findings);
  const std::string front = r.dom.substr(findings, index - findings);
  // Table 3.1's statistics agree to the printed digits: reproduced, with its row count.
  EXPECT_NE(front.find("thesis Table 3.1"), std::string::npos);
  EXPECT_NE(front.find("all 9 rows within"), std::string::npos) << front.substr(0, 2000);
  EXPECT_NE(front.find("class=\"v-reproduced\""), std::string::npos);
  // The quantization σ: the exact optimum, confirmed by the closed form, contradicts the thesis.
  EXPECT_NE(front.find("contradict the thesis"), std::string::npos) << front.substr(0, 3000);
  // The diagnosed log: its kept causes with intervals and held-out gains.
  EXPECT_NE(front.find("Real logs: what the diagnosis kept"), std::string::npos);
  EXPECT_NE(front.find("umbmark"), std::string::npos);
  EXPECT_NE(front.find("held-out"), std::string::npos);
  int binned = 0, profiles = 0, cdfs = 0;
  for (std::size_t at = r.dom.find("<figure class=\"chart\""); at != std::string::npos;
       at = r.dom.find("<figure class=\"chart\"", at + 1)) {
    const std::string f = r.dom.substr(at, r.dom.find("</figure>", at) - at);
    ASSERT_NE(f.find("<svg"), std::string::npos) << f.substr(0, 300);
    if (f.find("data-kind=\"binned\"") != std::string::npos) {
      ++binned;
      EXPECT_NE(f.find("nominal model"), std::string::npos);
      EXPECT_NE(f.find("with "), std::string::npos);
      EXPECT_GE(count_of(f, "gpPt6"), 10u) << f.substr(0, 300);  // the bins' points
    } else if (f.find("data-kind=\"profile\"") != std::string::npos) {
      ++profiles;
      EXPECT_GE(longest_path(f), 30u) << f.substr(0, 300);  // 61 offsets
    } else if (f.find("data-kind=\"cdf\"") != std::string::npos) {
      ++cdfs;
      EXPECT_GE(longest_path(f), 20u) << f.substr(0, 300);
    }
  }
  EXPECT_GE(binned, 1);
  EXPECT_EQ(profiles, 1);
  EXPECT_EQ(cdfs, 2);  // translation and heading error, nominal vs diagnosed
  const auto found = problems(r.log);
  EXPECT_TRUE(found.empty()) << found.front();
}

// The check above can fail: a page that logs to the console is caught.
TEST_F(HtmlReport, TheConsoleCheckCatchesAPageThatLogsAnError) {
  const auto html = dir.file("bad.html");
  std::ofstream(html) << "<!DOCTYPE html><html><body><script>console.error('boom');"
                         "undefined_function()</script></body></html>";
  const Rendered r = render(html, dir.path() / "profile");
  ASSERT_EQ(r.exit_code, 0) << r.log;
  const auto found = problems(r.log);
  ASSERT_EQ(found.size(), 2u) << r.log;  // the logged error and the uncaught exception
  EXPECT_NE(found[0].find("boom"), std::string::npos);
  EXPECT_NE(found[1].find("undefined_function"), std::string::npos);
}

TEST(ReportCommand, WithoutGnuplotExitsWith2AndSaysWhatToInstall) {
  testing::ScratchDir dir;
  ASSERT_EQ(run_locbench("run slip/normality_table_3_1 --out " + dir.path().string()).exit_code, 0);
  const Outcome o = testing::run_shell("LOCBENCH_GNUPLOT=/nonexistent/gnuplot " + std::string(LOCBENCH_EXE) +
                                       " report " + dir.path().string() + " -o " + dir.file("r.html").string());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("gnuplot-nox"), std::string::npos) << o.output;
  EXPECT_FALSE(std::filesystem::exists(dir.file("r.html")));
}

TEST(ReportCommand, RefusesAShardAndSaysToMergeFirst) {
  testing::ScratchDir dir;
  ASSERT_EQ(run_locbench("run slip/normality_table_3_1 --shard 1/1 --out " + dir.path().string()).exit_code, 0);
  const Outcome o = run_locbench("report " + dir.file("slip/normality_table_3_1.shard-1-of-1.json").string() + " -o " +
                                 dir.file("r.html").string());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("locbench merge"), std::string::npos) << o.output;
}

}  // namespace
}  // namespace locbench
