// Property: whatever Log the CARMEN writer accepts, reading its output gives the same Log.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include "datasets/io/carmen_reader.h"
#include "datasets/io/carmen_writer.h"
#include "io_test_support.h"
#include "log_generators.h"
#include "tests/test_data.h"

namespace locbench::io {
namespace {

using testing::log_difference;
using testing::random_carmen_log;

RC_GTEST_PROP(CarmenRoundTrip, ReadingWhatWasWrittenGivesTheSameLog, ()) {
  const Log log = random_carmen_log();
  const Log back = parse_carmen_log(format_carmen_log(log), "mem.clf");
  RC_ASSERT(log_difference(log, back) == std::string());
}

RC_GTEST_PROP(CarmenRoundTrip, WritingTwiceGivesTheSameText, ()) {
  const Log log = random_carmen_log();
  const std::string text = format_carmen_log(log);
  RC_ASSERT(format_carmen_log(parse_carmen_log(text, "mem.clf")) == text);
}

TEST(CarmenRoundTrip, FilesPlainAndGzipGiveTheSameLog) {
  testing::ScratchDir dir;
  int run = 0;
  const auto result = rc::check("file round trip", [&] {
    const Log log = random_carmen_log();
    const bool gz = *rc::gen::arbitrary<bool>();
    const auto path = dir.file(fmt::format("log{}{}", run++, gz ? ".clf.gz" : ".clf"));
    write_carmen_log(log, path);
    const Log back = read_carmen_log(path);
    RC_ASSERT(log_difference(log, back) == std::string());
    RC_ASSERT(back.source == path.string());
  });
  EXPECT_TRUE(result);
}

}  // namespace
}  // namespace locbench::io
