#include "reports/json_file.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "core/errors.h"

namespace locbench::reports {

nlohmann::json parse_json_text(const std::string& text, const std::string& source) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    const auto end = std::min<std::size_t>(e.byte, text.size());
    const auto line = 1 + static_cast<std::size_t>(
                              std::count(text.begin(), text.begin() + static_cast<long>(end), '\n'));
    throw InputError(source, line, std::string("invalid JSON: ") + e.what());
  } catch (const nlohmann::json::exception& e) {
    // nlohmann reports 1e400 as out_of_range.406 "number overflow parsing '1e400'".
    throw InputError(source, 0,
                     std::string(e.what()) + ": expected finite numbers (|x| < 1.8e308; JSON has no "
                                             "NaN or Infinity)");
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

}  // namespace locbench::reports
