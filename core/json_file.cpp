#include "core/json_file.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "core/errors.h"

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

}  // namespace

nlohmann::json parse_json_text(const std::string& text, const std::string& source) {
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
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw InputError(path.string(), 0, "is a folder: expected a " + what);
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), 0, "cannot open the " + what + ": " + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(path.string(), 0, "cannot read the " + what);
  return parse_json_text(text.str(), path.string());
}

}  // namespace locbench
