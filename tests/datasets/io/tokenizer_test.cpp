#include "datasets/io/tokenizer.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <limits>

#include "io_test_support.h"

namespace locbench::io {
namespace {

const std::string kFile = "f.clf";
const FieldContext kCtx{kFile, 7, "ODOM"};

TEST(Tokenizer, SplitsOnRunsOfSpacesTabsAndCarriageReturns) {
  std::vector<std::string_view> f;
  split_fields("  a\t\tb  c \r", f);
  EXPECT_EQ(f, (std::vector<std::string_view>{"a", "b", "c"}));
  split_fields("   ", f);
  EXPECT_TRUE(f.empty());
}

TEST(Tokenizer, ABlankLineOrOneWhoseFirstFieldStartsWithHashIsACommentAndNothingElseIs) {
  EXPECT_TRUE(is_blank_or_comment(""));
  EXPECT_TRUE(is_blank_or_comment(" \t\r"));
  EXPECT_TRUE(is_blank_or_comment("# a comment"));
  EXPECT_TRUE(is_blank_or_comment("  \t#ODOM 1 2 3"));
  EXPECT_FALSE(is_blank_or_comment("ODOM 1 2 3 # trailing"));
  EXPECT_FALSE(is_blank_or_comment(" x#"));
  // The same verdict as splitting and looking at the first field, on every short line of these bytes.
  const std::string bytes = " \t\r#a";
  std::vector<std::string_view> f;
  for (int n = 0; n < 6 * 6 * 6 * 6; ++n) {
    std::string line;
    for (int k = n, i = 0; i < 4; ++i, k /= 6) line.push_back(bytes[static_cast<std::size_t>(k % 6)]);
    split_fields(line, f);
    EXPECT_EQ(is_blank_or_comment(line), f.empty() || f[0][0] == '#') << '"' << line << '"';
  }
}

TEST(Tokenizer, ParsesDecimalAndExponentForms) {
  EXPECT_EQ(parse_finite("1", "x", kCtx), 1.0);
  EXPECT_EQ(parse_finite("-2.5e3", "x", kCtx), -2500.0);
  EXPECT_EQ(parse_finite("+.5", "x", kCtx), 0.5);
  EXPECT_EQ(parse_finite("976052857.337284", "x", kCtx), 976052857.337284);
  EXPECT_EQ(parse_int64("-9223372036854775808", "n", kCtx), std::numeric_limits<std::int64_t>::min());
  EXPECT_EQ(parse_int64("+12", "n", kCtx), 12);
}

TEST(Tokenizer, RejectsGarbageNanInfTrailingJunkAndOverflowNamingTheField) {
  for (const char* bad :
       {"", "abc", "1.0x", "nan", "NaN", "inf", "-infinity", "1e999", "0x10", "+", "+-1", "--1", "1,5", " 1"}) {
    EXPECT_TRUE(testing::throws_input_error([&] { parse_finite(bad, "theta", kCtx); }, kFile, 7,
                                            {"ODOM: theta: expected a finite number, found '"}))
        << bad;
  }
  for (const char* bad : {"1.0", "1e3", "9223372036854775808", "x", ""}) {
    EXPECT_TRUE(testing::throws_input_error([&] { parse_int64(bad, "left_ticks", kCtx); }, kFile, 7,
                                            {"left_ticks: expected an integer"}))
        << bad;
  }
}

TEST(Tokenizer, QuotesTokensEscapingBytesAndCuttingLongOnes) {
  EXPECT_EQ(quote_token("ab"), "'ab'");
  EXPECT_EQ(quote_token(std::string("a\0\xff", 3)), "'a\\x00\\xff'");
  EXPECT_EQ(quote_token(std::string(100, 'x')), fmt::format("'{}...'", std::string(40, 'x')));
}

}  // namespace
}  // namespace locbench::io
