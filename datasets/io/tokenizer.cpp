#include "datasets/io/tokenizer.h"

#include <charconv>
#include <cmath>
#include <system_error>

#include "core/errors.h"

namespace locbench::io {
namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// from_chars does not take a leading '+'; accept one (but not "+-1" or "+").
std::string_view strip_plus(std::string_view token) {
  if (token.size() > 1 && token[0] == '+' && token[1] != '-' && token[1] != '+') {
    token.remove_prefix(1);
  }
  return token;
}

std::string field_prefix(std::string_view field) { return field.empty() ? std::string() : std::string(field) + ": "; }

}  // namespace

void fail_input(const FieldContext& ctx, std::string_view what) {
  std::string msg;
  if (!ctx.record.empty()) {
    msg.append(ctx.record);
    msg.append(": ");
  }
  msg.append(what);
  throw InputError(ctx.file, ctx.line, msg);
}

void split_fields(std::string_view line, std::vector<std::string_view>& out) {
  out.clear();
  std::size_t i = 0;
  const std::size_t n = line.size();
  while (i < n) {
    while (i < n && is_space(line[i])) ++i;
    if (i == n) break;
    const std::size_t start = i;
    while (i < n && !is_space(line[i])) ++i;
    out.push_back(line.substr(start, i - start));
  }
}

bool is_blank_or_comment(std::string_view line) {
  std::size_t i = 0;
  while (i < line.size() && is_space(line[i])) ++i;
  return i == line.size() || line[i] == '#';
}

std::string quote_token(std::string_view token) {
  constexpr std::size_t kMax = 40;
  std::string out = "'";
  for (std::size_t i = 0; i < token.size() && i < kMax; ++i) {
    const auto c = static_cast<unsigned char>(token[i]);
    if (c >= 0x20 && c < 0x7f) {
      out.push_back(static_cast<char>(c));
    } else {
      constexpr const char* kHex = "0123456789abcdef";
      out += "\\x";
      out.push_back(kHex[c >> 4]);
      out.push_back(kHex[c & 0xf]);
    }
  }
  if (token.size() > kMax) out += "...";
  out += "'";
  return out;
}

bool try_parse_finite(std::string_view token, double& value) {
  token = strip_plus(token);
  if (token.empty()) return false;
  double v = 0.0;
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, v, std::chars_format::general);
  if (ec != std::errc() || ptr != end || !std::isfinite(v)) return false;
  value = v;
  return true;
}

bool try_parse_int64(std::string_view token, std::int64_t& value) {
  token = strip_plus(token);
  if (token.empty()) return false;
  std::int64_t v = 0;
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, v, 10);
  if (ec != std::errc() || ptr != end) return false;
  value = v;
  return true;
}

double parse_finite(std::string_view token, std::string_view field, const FieldContext& ctx) {
  double v = 0.0;
  if (!try_parse_finite(token, v)) {
    fail_input(ctx, field_prefix(field) + "expected a finite number, found " + quote_token(token));
  }
  return v;
}

std::int64_t parse_int64(std::string_view token, std::string_view field, const FieldContext& ctx) {
  std::int64_t v = 0;
  if (!try_parse_int64(token, v)) {
    fail_input(ctx, field_prefix(field) + "expected an integer, found " + quote_token(token));
  }
  return v;
}

void expect_field_count(std::span<const std::string_view> fields, std::size_t expected, const FieldContext& ctx) {
  if (fields.size() != expected) {
    fail_input(ctx, "expected " + std::to_string(expected) +
                        (ctx.record.empty() ? " fields, found " : " fields after the tag, found ") +
                        std::to_string(fields.size()));
  }
}

}  // namespace locbench::io
