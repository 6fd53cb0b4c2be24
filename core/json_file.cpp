#include "core/json_file.h"

#include <algorithm>
#include <cctype>

#include "core/errors.h"
#include "core/input_file.h"
#include "core/input_limits.h"

namespace locbench {
namespace {

// The word (letters, digits, sign, dot) around byte offset `at`.
std::string word_at(const std::string& text, std::size_t at) {
  if (text.empty()) return {};
  at = std::min(at, text.size() - 1);
  auto part = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.'; };
  std::size_t b = at, e = at;
  while (b > 0 && part(text[b - 1])) --b;
  while (e < text.size() && part(text[e])) ++e;
  return text.substr(b, e - b);
}

bool names_non_finite(std::string w) {
  std::transform(w.begin(), w.end(), w.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (!w.empty() && (w[0] == '-' || w[0] == '+')) w.erase(0, 1);
  return w == "nan" || w == "inf" || w == "infinity";
}

std::size_t line_of(const std::string& text, std::size_t byte) {
  const auto end = static_cast<std::ptrdiff_t>(std::min(byte, text.size()));
  return 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + end, '\n'));
}

// Refuses text whose arrays and objects nest deeper than the limit, before the parser builds
// a document whose copies and destruction recurse once per level (a 100,000-deep array
// overflowed the stack). Brackets inside strings do not count.
void check_nesting(const std::string& text, const std::string& source) {
  const auto max_depth = static_cast<std::size_t>(limits::kJsonDepth.max);
  std::size_t depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') {
        ++i;
      } else if (c == '"') {
        in_string = false;
      }
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > max_depth) {
        throw InputError(source, line_of(text, i),
                         "arrays and objects nest more than " + limits::limit_text(limits::kJsonDepth.max) +
                             " levels deep: expected at most that (see `locbench --help`, \"Input limits\")");
      }
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
}

}  // namespace

nlohmann::json parse_json_text(const std::string& text, const std::string& source) {
  check_nesting(text, source);
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    const std::size_t at = e.byte > 0 ? e.byte - 1 : 0;
    const std::string word = word_at(text, at);
    if (names_non_finite(word)) {
      throw InputError(source, line_of(text, at),
                       "'" + word +
                           "' is not a JSON number: NaN and Infinity are not allowed; every value "
                           "must be a finite number");
    }
    throw InputError(source, line_of(text, e.byte), std::string("invalid JSON: ") + e.what());
  } catch (const nlohmann::json::exception& e) {
    // nlohmann reports 1e400 as out_of_range.406 "number overflow parsing '1e400'".
    const std::string what = e.what();
    const auto open = what.find('\'');
    const auto close = what.rfind('\'');
    if (open != std::string::npos && close > open) {
      const std::string token = what.substr(open + 1, close - open - 1);
      const auto at = text.find(token);
      throw InputError(source, at == std::string::npos ? 0 : line_of(text, at),
                       "'" + token +
                           "' is not a finite number (number overflow: it exceeds a double); expected "
                           "finite numbers (|x| < 1.8e308; JSON has no NaN or Infinity)");
    }
    throw InputError(source, 0, what + ": expected finite numbers (|x| < 1.8e308; JSON has no NaN or Infinity)");
  }
}

nlohmann::json read_json_file(const std::filesystem::path& path, const std::string& what) {
  InputFile in(path, what, static_cast<std::uint64_t>(limits::kJsonFileBytes.max));
  return parse_json_text(in.read_all(), path.string());
}

}  // namespace locbench
