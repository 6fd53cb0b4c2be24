#include "datasets/io/relations_reader.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include "datasets/io/relations_writer.h"
#include "io_test_support.h"
#include "log_generators.h"
#include "tests/test_data.h"

namespace locbench::io {
namespace {

TEST(RelationsReader, ReadsTimesAndPlanarMotionIgnoringZRollPitch) {
  const auto rel = parse_relations(
      "# timestamp1 timestamp2 x y z roll pitch yaw\n"
      "1134864645.90321 1134864646.32420 0.31293 0.02935 0.00000  0.00000 0.00000 0.24198\n"
      "\n976052905.167303\t976052911.885496 -0.056990 -0.128430 0.1 0.2 -0.000000 -1.682210\r\n",
      "x.relations");
  ASSERT_EQ(rel.size(), 2u);
  EXPECT_EQ(rel[0].t1, 1134864645.90321);
  EXPECT_EQ(rel[0].t2, 1134864646.32420);
  EXPECT_EQ(rel[0].delta.x, 0.31293);
  EXPECT_EQ(rel[0].delta.y, 0.02935);
  EXPECT_EQ(rel[0].delta.theta, 0.24198);
  EXPECT_EQ(rel[1].delta.theta, -1.682210);
}

TEST(RelationsReader, ReadsGzipFiles) {
  testing::ScratchDir dir;
  testing::write_bytes(dir.file("a.relations.gz"), testing::gzip("1 2 3 4 0 0 0 0.5\n"));
  const auto rel = read_relations(dir.file("a.relations.gz"));
  ASSERT_EQ(rel.size(), 1u);
  EXPECT_EQ(rel[0].delta.theta, 0.5);
}

TEST(RelationsWriter, WritesZeroZRollPitchAndShortestNumbers) {
  EXPECT_EQ(format_relations({{1.5, 2.25, Pose2(0.1, -0.2, 0.3)}}),
            "# t1 t2 x y z roll pitch yaw\n1.5 2.25 0.1 -0.2 0 0 0 0.3\n");
}

RC_GTEST_PROP(RelationsRoundTrip, ReadingWhatWasWrittenGivesTheSameRelations, ()) {
  const auto count = *rc::gen::inRange<std::size_t>(0, 30);
  std::vector<Relation> rel;
  for (std::size_t i = 0; i < count; ++i) {
    rel.push_back({*testing::gen_finite(), *testing::gen_finite(), *testing::gen_pose()});
  }
  const auto back = parse_relations(format_relations(rel), "m.relations");
  RC_ASSERT(back.size() == rel.size());
  for (std::size_t i = 0; i < rel.size(); ++i) {
    RC_ASSERT(back[i].t1 == rel[i].t1);
    RC_ASSERT(back[i].t2 == rel[i].t2);
    RC_ASSERT(testing::same_pose(back[i].delta, rel[i].delta));
  }
}

TEST(RelationsRoundTrip, GzipFileRoundTrip) {
  testing::ScratchDir dir;
  const std::vector<Relation> rel = {{1, 2, Pose2(0.1, 0.2, 0.3)}, {2, 3, Pose2(-1, 1e-9, -3)}};
  write_relations(rel, dir.file("r.relations.gz"));
  const auto back = read_relations(dir.file("r.relations.gz"));
  ASSERT_EQ(back.size(), 2u);
  EXPECT_TRUE(testing::same_pose(back[1].delta, rel[1].delta));
}

}  // namespace
}  // namespace locbench::io
