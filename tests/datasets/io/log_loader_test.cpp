#include "datasets/io/log_loader.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "io_test_support.h"
#include "tests/test_data.h"

namespace locbench::io {
namespace {

using testing::ScratchDir;
using testing::write_bytes;

TEST(LogLoader, PicksTheCarmenReaderForClfLogAndCarmenFilesPlainOrGzip) {
  ScratchDir dir;
  const std::string text = "ODOM 1 2 0 0 0 0 1 h 1\n";
  for (const std::string name : {"a.clf", "b.log", "c.carmen", "d.clf.gz", "e.LOG.GZ"}) {
    const bool gz = name.size() > 3 && (name.ends_with(".gz") || name.ends_with(".GZ"));
    write_bytes(dir.file(name), gz ? testing::gzip(text) : text);
    const Log log = load_log(dir.file(name).string());
    EXPECT_EQ(log.odometry.size(), 1u) << name;
  }
}

TEST(LogLoader, LoadsRelationsFilesAsLogsWithOnlyRelations) {
  ScratchDir dir;
  write_bytes(dir.file("aces.relations.gz"), testing::gzip("1 2 3 4 0 0 0 0.5\n"));
  const Log log = load_log(dir.file("aces.relations.gz").string());
  EXPECT_EQ(log.relations.size(), 1u);
  EXPECT_EQ(log.record_count(), 1u);
  EXPECT_EQ(log.name, "aces");
}

TEST(LogLoader, LoadsMrclamFoldersWithOptionalRobotSuffix) {
  ScratchDir dir;
  for (int robot : {1, 3}) {
    const std::string stem = fmt::format("Robot{}_", robot);
    write_bytes(dir.file(stem + "Odometry.dat"), "# h\n1 0.1 0\n2 0.1 0\n");
    write_bytes(dir.file(stem + "Groundtruth.dat"), "# h\n1 0 0 0\n");
    write_bytes(dir.file(stem + "Measurement.dat"), "# h\n");
  }
  EXPECT_EQ(load_log(dir.path().string()).params.at("mrclam_robot"), "1");
  EXPECT_EQ(load_log(dir.path().string() + "#robot3").params.at("mrclam_robot"), "3");
  EXPECT_TRUE(testing::throws_input_error([&] { load_log(dir.path().string() + "#robot2"); }, "Robot2_Odometry.dat", 0,
                                          {"missing MRCLAM file"}));
}

TEST(LogLoader, AttachesRelationsToALog) {
  ScratchDir dir;
  write_bytes(dir.file("x.relations"), "1 2 3 4 0 0 0 0.5\n3 4 0 0 0 0 0 0\n");
  Log log;
  attach_relations(log, dir.file("x.relations"));
  EXPECT_EQ(log.relations.size(), 2u);
}

}  // namespace
}  // namespace locbench::io
