#include "datasets/io/line_reader.h"

#include <gtest/gtest.h>

#include <vector>

#include "core/errors.h"
#include "io_test_support.h"
#include "tests/test_data.h"

namespace locbench::io {
namespace {

std::vector<std::string> all_lines(LineReader& r) {
  std::vector<std::string> out;
  std::string_view line;
  while (r.next(line)) out.emplace_back(line);
  return out;
}

TEST(LineReader, SplitsOnNewlinesStripsCarriageReturnsAndCountsLines) {
  LineReader r("a\r\n\nb c\nlast", "mem");
  std::string_view line;
  ASSERT_TRUE(r.next(line));
  EXPECT_EQ(line, "a");
  EXPECT_EQ(r.line_number(), 1u);
  ASSERT_TRUE(r.next(line));
  EXPECT_EQ(line, "");
  ASSERT_TRUE(r.next(line));
  EXPECT_EQ(line, "b c");
  ASSERT_TRUE(r.next(line));
  EXPECT_EQ(line, "last");
  EXPECT_EQ(r.line_number(), 4u);
  EXPECT_FALSE(r.next(line));
  EXPECT_FALSE(r.next(line));
}

TEST(LineReader, ReadsLongLinesAcrossBufferBoundariesFromPlainAndGzipFiles) {
  testing::ScratchDir dir;
  std::string text;
  std::vector<std::string> expected;
  for (int i = 0; i < 50; ++i) {
    expected.push_back(std::string(static_cast<std::size_t>(1 + i * 7919 % 40000), 'a' + static_cast<char>(i % 26)));
    text += expected.back() + "\n";
  }
  testing::write_bytes(dir.file("p.txt"), text);
  testing::write_bytes(dir.file("g.txt.gz"), testing::gzip(text));
  LineReader plain(dir.file("p.txt"));
  LineReader packed(dir.file("g.txt.gz"));
  EXPECT_EQ(all_lines(plain), expected);
  EXPECT_EQ(all_lines(packed), expected);
  EXPECT_EQ(packed.line_number(), 50u);
}

// The decompressed bytes count against the limit: a gzip bomb stops at it with the reason.
TEST(LineReader, ReadsGzipDecompressingToTheLimitAndStopsOneByteBeyond) {
  testing::ScratchDir dir;
  const std::string at(1000, '\n');
  testing::write_bytes(dir.file("at.gz"), testing::gzip("x" + at.substr(1)));
  testing::write_bytes(dir.file("past.gz"), testing::gzip("x" + at));
  LineReader ok(dir.file("at.gz"), 1000);
  EXPECT_EQ(all_lines(ok).size(), 999u);  // "x" and 998 empty lines
  LineReader past(dir.file("past.gz"), 1000);
  try {
    all_lines(past);
    ADD_FAILURE() << "no error past the limit";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("past.gz: decompresses to more than 1000 bytes"), std::string::npos)
        << e.what();
  }
}

TEST(LineReader, KeepsNulBytesInsideLines) {
  const std::string text("a\0b\n", 4);
  LineReader r(text, "mem");
  std::string_view line;
  ASSERT_TRUE(r.next(line));
  EXPECT_EQ(line.size(), 3u);
}

TEST(LineReader, RejectsWhitespaceOnlyInput) {
  EXPECT_TRUE(testing::throws_input_error(
      [] {
        LineReader r(" \n\t\r\n", "blank.txt");
        all_lines(r);
      },
      "blank.txt", 0, {"empty file"}));
}

}  // namespace
}  // namespace locbench::io
