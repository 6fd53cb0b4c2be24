#pragma once
// Splitting a text line into whitespace-separated fields, and strict number parsing that names
// the file, line, record and field when a token is not what was expected.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace locbench::io {

// Where a record comes from, for error messages: "file:line: RECORD: ...".
struct FieldContext {
  const std::string& file;
  std::size_t line = 0;
  std::string_view record;  // e.g. "ODOM"; empty for formats without record tags
};

// Throws InputError naming the file and line; `what` is prefixed with the record name.
[[noreturn]] void fail_input(const FieldContext& ctx, std::string_view what);

// Splits on spaces, tabs, \r, \v and \f (any run of them); `out` is cleared first and its
// capacity reused. The views point into `line`.
void split_fields(std::string_view line, std::vector<std::string_view>& out);
// True when the line has no field or its first field starts with '#' (a comment): such a line
// need not be split.
bool is_blank_or_comment(std::string_view line);

// A token as printed in error messages: quoted, non-printable bytes escaped, long ones cut.
std::string quote_token(std::string_view token);

// Parses the whole token as a finite decimal number ("1", "-2.5e3", "+.5"); rejects garbage,
// trailing junk, NaN, infinities and out-of-range values with an InputError naming `field`.
double parse_finite(std::string_view token, std::string_view field, const FieldContext& ctx);
// Parses the whole token as a signed decimal integer that fits in 64 bits.
std::int64_t parse_int64(std::string_view token, std::string_view field, const FieldContext& ctx);

// The same without throwing: false if the token is not a finite number / a 64-bit integer.
bool try_parse_finite(std::string_view token, double& value);
bool try_parse_int64(std::string_view token, std::int64_t& value);

// Throws unless `fields` (the tokens after the record tag) has exactly `expected` entries.
void expect_field_count(std::span<const std::string_view> fields, std::size_t expected, const FieldContext& ctx);

}  // namespace locbench::io
