// Readers of the calibration data sets: Censi et al.'s tuples and published results, and the
// relative-motion files of stachniss_ls_calib and grisetti_diffdrive.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include "datasets/io/censi_results_reader.h"
#include "datasets/io/censi_tuple_reader.h"
#include "datasets/io/relative_motion_reader.h"
#include "io_test_support.h"
#include "log_generators.h"
#include "tests/test_data.h"

namespace locbench::io {
namespace {

using testing::throws_input_error;

const std::string kTuples =
    "{ \"T\": 7.943960e-01, \"phi_l\": 1.401765e-01, \"phi_r\": -1.373157e-01, "
    "\"sm\": [ 1.092608e-03, -5.089714e-04, -2.748851e-02 ] }\n"
    "{ \"T\": 0.5, \"phi_l\": 1, \"phi_r\": 2, \"sm\": [0.1, 0.2, 0.3] }"
    "{ \"T\": 0.25, \"phi_l\": -1, \"phi_r\": -2, \"sm\": [0, 0, 0], \"extra\": \"ignored\" }\n";

TEST(CensiTupleReader, ReadsIntervalWheelSpeedsAndScanMatchedDisplacement) {
  const auto t = parse_censi_tuples(kTuples, "a.tuple");
  ASSERT_EQ(t.size(), 3u);
  EXPECT_EQ(t[0].T, 7.943960e-01);
  EXPECT_EQ(t[0].phi_l, 1.401765e-01);
  EXPECT_EQ(t[0].phi_r, -1.373157e-01);
  EXPECT_EQ(t[0].sm.x, 1.092608e-03);
  EXPECT_EQ(t[0].sm.y, -5.089714e-04);
  EXPECT_EQ(t[0].sm.theta, -2.748851e-02);
  // Two objects on one line (as in the published full sets): both read.
  EXPECT_EQ(t[1].T, 0.5);
  EXPECT_EQ(t[2].T, 0.25);
  EXPECT_EQ(t[2].phi_r, -2.0);
}

TEST(CensiTupleReader, ReadsGzipFiles) {
  testing::ScratchDir dir;
  testing::write_bytes(dir.file("a.tuple.gz"), testing::gzip(kTuples));
  EXPECT_EQ(read_censi_tuples(dir.file("a.tuple.gz")).size(), 3u);
}

TEST(CensiTupleReader, RejectsMalformedTuplesNamingFileLineAndKey) {
  const std::string ok = "{\"T\": 1, \"phi_l\": 1, \"phi_r\": 1, \"sm\": [0, 0, 0]}\n";
  auto parse = [](std::string text) { return [text] { parse_censi_tuples(text, "b.tuple"); }; };
  EXPECT_TRUE(throws_input_error(parse(ok + "{\"T\": 1, \"phi_l\": 1, \"sm\": [0, 0, 0]}\n"), "b.tuple", 2,
                                 {"phi_r", "missing"}));
  EXPECT_TRUE(throws_input_error(parse(ok + ok + "{\"T\": NaN, \"phi_l\": 1}\n"), "b.tuple", 3, {"expected JSON"}));
  EXPECT_TRUE(throws_input_error(parse("{\"T\": 0, \"phi_l\": 1, \"phi_r\": 1, \"sm\": [0,0,0]}"), "b.tuple", 1,
                                 {"\"T\"", "> 0"}));
  EXPECT_TRUE(throws_input_error(parse("{\"T\": 1, \"phi_l\": 1, \"phi_r\": 1, \"sm\": [0, 0]}"), "b.tuple", 1,
                                 {"\"sm\"", "3 numbers"}));
  EXPECT_TRUE(throws_input_error(parse("{\"T\": 1, \"phi_l\": \"1\", \"phi_r\": 1, \"sm\": [0, 0, 0]}"), "b.tuple", 1,
                                 {"\"phi_l\"", "a number", "a string"}));
  EXPECT_TRUE(throws_input_error(parse("[1, 2, 3]\n"), "b.tuple", 1, {"JSON object"}));
  EXPECT_TRUE(throws_input_error(parse(ok + "{\"T\": 1e999}"), "b.tuple", 2, {"JSON"}));
  EXPECT_TRUE(throws_input_error(parse("  \n\n"), "b.tuple", 0, {}));
}

RC_GTEST_PROP(CensiTupleReader, ReadingWhatWasWrittenGivesTheSameTuples, ()) {
  const auto count = *rc::gen::inRange<std::size_t>(1, 20);
  std::vector<WheelSpeedTuple> in;
  std::string text;
  for (std::size_t i = 0; i < count; ++i) {
    WheelSpeedTuple t;
    t.T = std::abs(*testing::gen_finite()) + 1e-3;
    t.phi_l = *testing::gen_finite();
    t.phi_r = *testing::gen_finite();
    t.sm = *testing::gen_pose();
    in.push_back(t);
    text += fmt::format("{{ \"T\": {}, \"phi_l\": {}, \"phi_r\": {}, \"sm\": [ {}, {}, {} ] }}", t.T, t.phi_l, t.phi_r,
                        t.sm.x, t.sm.y, t.sm.theta);
    text += *rc::gen::element(std::string("\n"), std::string(" "), std::string("\r\n"));
  }
  const auto out = parse_censi_tuples(text, "p.tuple");
  RC_ASSERT(out.size() == in.size());
  for (std::size_t i = 0; i < in.size(); ++i) {
    RC_ASSERT(out[i].T == in[i].T);
    RC_ASSERT(out[i].phi_l == in[i].phi_l);
    RC_ASSERT(out[i].phi_r == in[i].phi_r);
    RC_ASSERT(testing::same_pose(out[i].sm, in[i].sm));
  }
}

const std::string kResults =
    "{ \"axle\": 0.0878146, \"l_diam\": 0.0410529, \"r_diam\": 0.041384, \"l_x\": -0.00265427, "
    "\"l_y\": 0.00583491, \"l_theta\": -1.55197, \"E_d\": 1.00807, \"E_b\": 0.975718, "
    "\"covariance\": [ [ 4, 0, 0, 0, 0, 0 ], [ 0, 9, 0, 0, 0, 0 ], [ 0, 0, 16, 0, 0, 1 ], "
    "[ 0, 0, 0, 1, 0, 0 ], [ 0, 0, 0, 0, 1, 0 ], [ 0, 0, 1, 0, 0, 25 ] ] }\n";

TEST(CensiResultsReader, ReadsTheSolutionAndItsCovarianceOfRadii) {
  const CensiPublishedResult r = parse_censi_results(kResults, "x_results.json");
  EXPECT_EQ(r.axle, 0.0878146);
  EXPECT_EQ(r.left_diameter, 0.0410529);
  EXPECT_DOUBLE_EQ(r.left_radius(), 0.02052645);
  EXPECT_EQ(r.right_diameter, 0.041384);
  EXPECT_EQ(r.sensor_x, -0.00265427);
  EXPECT_EQ(r.sensor_y, 0.00583491);
  EXPECT_EQ(r.sensor_theta, -1.55197);
  EXPECT_EQ(r.E_d, 1.00807);
  EXPECT_EQ(r.E_b, 0.975718);
  EXPECT_EQ(r.covariance(2, 5), 1.0);
  EXPECT_EQ(r.standard_error(0), 2.0);
  EXPECT_EQ(r.standard_error(5), 5.0);
}

TEST(CensiResultsReader, RejectsMissingKeysBadCovariancesAndBadJson) {
  auto parse = [](std::string text) { return [text] { parse_censi_results(text, "y.json"); }; };
  std::string no_axle = kResults;
  no_axle.replace(no_axle.find("\"axle\""), 6, "\"axel\"");
  EXPECT_TRUE(throws_input_error(parse(no_axle), "y.json", 1, {"\"axle\""}));
  std::string asym = kResults;
  asym.replace(asym.find("[ 0, 0, 1, 0, 0, 25 ]"), 21, "[ 0, 0, 2, 0, 0, 25 ]");
  EXPECT_TRUE(throws_input_error(parse(asym), "y.json", 1, {"not symmetric"}));
  std::string five = kResults;
  five.replace(five.find("[ 0, 0, 0, 0, 1, 0 ], "), 22, "");
  EXPECT_TRUE(throws_input_error(parse(five), "y.json", 1, {"6 rows"}));
  EXPECT_TRUE(throws_input_error(parse("\n\n{ \"axle\": 1,\n  oops }"), "y.json", 4, {"expected JSON"}));
}

TEST(RelativeMotionReader, PairsTheRowsOfTheTwoFiles) {
  const auto p = parse_relative_motion_pairs(" 0 0 0\n 0.113 -8.3e-05 0\n", "odom.txt",
                                             "# scan\n 0 0 0\n\n 0.113001 -0.000942 0.003906\n", "sm.txt");
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[1].odometry.x, 0.113);
  EXPECT_EQ(p[1].odometry.y, -8.3e-05);
  EXPECT_EQ(p[1].reference.x, 0.113001);
  EXPECT_EQ(p[1].reference.theta, 0.003906);
}

TEST(RelativeMotionReader, DifferentRowCountsAreAnErrorNamingBothFiles) {
  EXPECT_TRUE(throws_input_error([] { parse_relative_motion_pairs("0 0 0\n1 0 0\n", "odom.txt", "0 0 0\n", "sm.txt"); },
                                 "sm.txt", 0, {"1 motion rows", "odom.txt has 2"}));
}

TEST(RelativeMotionReader, MalformedRowsNameFileLineAndField) {
  EXPECT_TRUE(
      throws_input_error([] { parse_relative_motion_pairs("0 0 0\n1 0\n", "odom.txt", "0 0 0\n1 0 0\n", "sm.txt"); },
                         "odom.txt", 2, {"expected 3 fields"}));
  EXPECT_TRUE(throws_input_error([] { parse_relative_motion_pairs("0 0 0\n", "odom.txt", "0 nan 0\n", "sm.txt"); },
                                 "sm.txt", 1, {"dy"}));
}

TEST(TickMotionReader, ReadsTicksAndReferenceMotion) {
  const auto rows = parse_tick_motions(
      "0 0 -0.000735349  1.50913e-05  0.000174196\n-0.0212839  0.0210924   0.0154077 "
      "0.000291585  -0.0023148\n",
      "dd.txt");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[1].left, -0.0212839);
  EXPECT_EQ(rows[1].right, 0.0210924);
  EXPECT_EQ(rows[1].reference.x, 0.0154077);
  EXPECT_EQ(rows[1].reference.theta, -0.0023148);
  EXPECT_TRUE(
      throws_input_error([] { parse_tick_motions("1 2 3 4 5\n1 2 3 4 x\n", "dd.txt"); }, "dd.txt", 2, {"theta"}));
  EXPECT_TRUE(
      throws_input_error([] { parse_tick_motions("1 2 3 4 5 6\n", "dd.txt"); }, "dd.txt", 1, {"expected 5 fields"}));
}

RC_GTEST_PROP(RelativeMotionReader, ReadingWhatWasWrittenGivesTheSameRows, ()) {
  const auto count = *rc::gen::inRange<std::size_t>(1, 30);
  std::string odom, ref, ticks;
  std::vector<RelativeMotionPair> pairs;
  std::vector<TickMotion> rows;
  for (std::size_t i = 0; i < count; ++i) {
    const Pose2 a = *testing::gen_pose(), b = *testing::gen_pose();
    const double l = *testing::gen_finite(), r = *testing::gen_finite();
    pairs.push_back({a, b});
    rows.push_back({l, r, b});
    odom += fmt::format("{} {} {}\n", a.x, a.y, a.theta);
    ref += fmt::format(" {}\t{} {}\n", b.x, b.y, b.theta);
    ticks += fmt::format("{} {} {} {} {}\n", l, r, b.x, b.y, b.theta);
  }
  const auto p = parse_relative_motion_pairs(odom, "o", ref, "r");
  const auto t = parse_tick_motions(ticks, "t");
  RC_ASSERT(p.size() == count);
  RC_ASSERT(t.size() == count);
  for (std::size_t i = 0; i < count; ++i) {
    RC_ASSERT(testing::same_pose(p[i].odometry, pairs[i].odometry));
    RC_ASSERT(testing::same_pose(p[i].reference, pairs[i].reference));
    RC_ASSERT(t[i].left == rows[i].left);
    RC_ASSERT(t[i].right == rows[i].right);
    RC_ASSERT(testing::same_pose(t[i].reference, rows[i].reference));
  }
}

TEST(CalibrationRealData, CensiKheperaTupleFilesHoldThePublishedSampleCounts) {
  LOCBENCH_REQUIRE_DATA("calibration/censi_khepera");
  const auto dir = catalog::data_root() / "calibration/censi_khepera";
  EXPECT_EQ(read_censi_tuples(dir / "lstraight_0.tuple.gz").size(), 1466u);
  EXPECT_EQ(read_censi_tuples(dir / "lstraight_1.tuple.gz").size(), 1465u);
  EXPECT_EQ(read_censi_tuples(dir / "lstraight_2.tuple.gz").size(), 1465u);
  // The full set is the three subsets concatenated (three lines hold two objects).
  EXPECT_EQ(read_censi_tuples(dir / "lstraight.tuple.gz").size(), 1466u + 1465u + 1465u);
  EXPECT_EQ(read_censi_tuples(dir / "l90.tuple.gz").size(), 1099u + 1098u + 1098u);
  const auto r = read_censi_results(dir / "l90_results.json");
  EXPECT_EQ(r.axle, 0.0880134);
  EXPECT_EQ(r.covariance(0, 0), 3.91817e-07);
}

TEST(CalibrationRealData, StachnissAndGrisettiFilesRead) {
  LOCBENCH_REQUIRE_DATA("calibration/stachniss_ls_calib");
  LOCBENCH_REQUIRE_DATA("calibration/grisetti_diffdrive");
  const auto root = catalog::data_root() / "calibration";
  const auto pairs = read_relative_motion_pairs(root / "stachniss_ls_calib/odom_motions.txt.gz",
                                                root / "stachniss_ls_calib/scanmatched_motions.txt.gz");
  EXPECT_EQ(pairs.size(), 2000u);
  const auto rows = read_tick_motions(root / "grisetti_diffdrive/differential_drive_calibration.txt.gz");
  EXPECT_EQ(rows.size(), 487u);
}

}  // namespace
}  // namespace locbench::io
