#pragma once
// The data lines of a whitespace-separated text format (TUM, .relations, relative-motion files,
// MRCLAM): blank lines and lines starting with '#' are skipped, every other line must have a
// fixed number of fields; errors name the file and line.
#include <array>
#include <cstddef>
#include <string_view>
#include <vector>

#include "datasets/io/line_reader.h"
#include "datasets/io/tokenizer.h"

namespace locbench::io {

// Calls on_row(fields, ctx) for each data line of `reader` (blank lines and # comments skipped).
template <typename OnRow>
void for_each_data_line(LineReader& reader, OnRow on_row) {
  std::vector<std::string_view> tokens;
  std::string_view line;
  while (reader.next(line)) {
    if (is_blank_or_comment(line)) continue;
    split_fields(line, tokens);
    const FieldContext ctx{reader.source(), reader.line_number(), {}};
    on_row(tokens, ctx);
  }
}

// The same after checking that each data line has `field_count` fields.
template <typename OnRow>
void for_each_data_line(LineReader& reader, std::size_t field_count, OnRow on_row) {
  for_each_data_line(reader, [&](const std::vector<std::string_view>& fields, const FieldContext& ctx) {
    expect_field_count(fields, field_count, ctx);
    on_row(fields, ctx);
  });
}

// The same for N numeric columns named `names`: on_row(values, ctx), every value parsed as a
// finite number.
template <std::size_t N, typename OnRow>
void for_each_numeric_row(LineReader& reader, const std::array<const char*, N>& names, OnRow on_row) {
  for_each_data_line(reader, N, [&](const std::vector<std::string_view>& fields, const FieldContext& ctx) {
    std::array<double, N> v{};
    for (std::size_t i = 0; i < N; ++i) v[i] = parse_finite(fields[i], names[i], ctx);
    on_row(v, ctx);
  });
}

}  // namespace locbench::io
