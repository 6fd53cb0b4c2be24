#include "reports/gnuplot_svg.h"

#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include "core/errors.h"
#include "core/output_file.h"

namespace locbench::reports {
namespace {

std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

bool executable(const std::filesystem::path& p) {
  return std::filesystem::is_regular_file(p) && access(p.c_str(), X_OK) == 0;
}

// A fresh, private temporary folder removed on scope exit.
struct TempDir {
  std::filesystem::path path;
  TempDir() {
    std::error_code ec;
    const std::filesystem::path base = std::filesystem::temp_directory_path(ec);
    if (ec) {
      const char* env = std::getenv("TMPDIR");
      throw InputError(
          env ? env : "$TMPDIR", 0,
          "cannot use the temporary folder for gnuplot: " + ec.message() + " (set TMPDIR to a writable folder)");
    }
    std::string tmpl = (base / "locbench-gnuplot-XXXXXX").string();
    if (!mkdtemp(tmpl.data())) {
      throw InputError(tmpl, 0,
                       std::string("cannot create a temporary folder for gnuplot: ") + std::strerror(errno) +
                           " (set TMPDIR to a writable folder)");
    }
    path = tmpl;
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
};

}  // namespace

std::optional<std::filesystem::path> find_gnuplot() {
  if (const char* env = std::getenv("LOCBENCH_GNUPLOT"); env && *env) {
    if (executable(env)) return std::filesystem::path(env);
    return std::nullopt;
  }
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (dir.empty()) continue;
    const std::filesystem::path p = std::filesystem::path(dir) / "gnuplot";
    if (executable(p)) return p;
  }
  return std::nullopt;
}

// `text` in single quotes for the shell, each ' written as '\''.
std::string shell_quoted(const std::string& text) {
  std::string out = "'";
  for (const char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string run_gnuplot(const std::filesystem::path& gnuplot, const std::string& script) {
  TempDir dir;
  const auto script_path = dir.path / "chart.gp";
  const auto svg_path = dir.path / "chart.svg";
  const auto err_path = dir.path / "stderr.txt";
  write_file_atomically(script_path, script);  // checked: a full $TMPDIR is an error, exit 2
  // Paths are ours (no quotes in them); gnuplot's path may come from $LOCBENCH_GNUPLOT.
  const std::string quoted = shell_quoted(gnuplot.string());
  const std::string cmd =
      quoted + " '" + script_path.string() + "' > '" + svg_path.string() + "' 2> '" + err_path.string() + "'";
  const int status = std::system(cmd.c_str());
  const std::string svg = read_file(svg_path);
  if (status != 0 || svg.find("<svg") == std::string::npos) {
    throw InputError(
        svg_path.string(), 0,
        "gnuplot failed (" + gnuplot.string() + "; is $TMPDIR full or unwritable?): " + read_file(err_path));
  }
  return svg;
}

std::vector<std::string> run_gnuplot_batch(const std::filesystem::path& gnuplot,
                                           const std::vector<std::string>& scripts) {
  if (scripts.empty()) return {};
  TempDir dir;
  const auto script_path = dir.path / "charts.gp";
  const auto err_path = dir.path / "stderr.txt";
  std::string all;
  for (std::size_t i = 0; i < scripts.size(); ++i) {
    // Datablocks persist across `reset`: undefine them so one chart never draws another's data.
    all += "reset\nundefine $*\nset output '" + (dir.path / ("chart" + std::to_string(i) + ".svg")).string() + "'\n";
    all += scripts[i];
    all += "unset output\n";
  }
  write_file_atomically(script_path, all);
  const std::string quoted = shell_quoted(gnuplot.string());
  const std::string cmd = quoted + " '" + script_path.string() + "' > /dev/null 2> '" + err_path.string() + "'";
  const int status = std::system(cmd.c_str());
  std::vector<std::string> svgs;
  svgs.reserve(scripts.size());
  for (std::size_t i = 0; i < scripts.size(); ++i) {
    const auto svg_path = dir.path / ("chart" + std::to_string(i) + ".svg");
    std::string svg = read_file(svg_path);
    if (status != 0 || svg.find("<svg") == std::string::npos) {
      throw InputError(svg_path.string(), 0,
                       "gnuplot failed on chart " + std::to_string(i + 1) + " of " + std::to_string(scripts.size()) +
                           " (" + gnuplot.string() + "; is $TMPDIR full or unwritable?): " + read_file(err_path));
    }
    svgs.push_back(std::move(svg));
  }
  return svgs;
}

std::set<std::string> element_ids(const std::string& svg) {
  std::set<std::string> ids;
  std::size_t p = svg.find("id=");
  while (p != std::string::npos) {
    const bool starts_word = p == 0 || !(std::isalnum(static_cast<unsigned char>(svg[p - 1])) || svg[p - 1] == '_');
    const std::size_t open = p + 3;  // the opening quote
    std::size_t next = open;
    if (starts_word && open < svg.size() && (svg[open] == '"' || svg[open] == '\'')) {
      const std::size_t close = svg.find_first_of("'\"", open + 1);
      if (close != std::string::npos && svg[close] == svg[open] && close > open + 1) {
        ids.insert(svg.substr(open + 1, close - open - 1));
        next = close + 1;  // matches do not overlap
      }
    }
    p = svg.find("id=", next);
  }
  return ids;
}

std::string inline_svg(const std::string& svg, const std::string& prefix) {
  std::string s = svg;
  const auto start = s.find("<svg");
  if (start != std::string::npos) s = s.substr(start);
  const std::set<std::string> ids = element_ids(s);
  for (const std::string& id : ids) {
    const std::string to = prefix + id;
    for (const std::string& q : {std::string("'"), std::string("\"")}) {
      for (const std::string& pre : {std::string("id="), std::string("href=")}) {
        const std::string from_text = pre + q + (pre == "href=" ? "#" : "") + id + q;
        const std::string to_text = pre + q + (pre == "href=" ? "#" : "") + to + q;
        for (std::size_t p = s.find(from_text); p != std::string::npos; p = s.find(from_text, p + to_text.size())) {
          s.replace(p, from_text.size(), to_text);
        }
      }
    }
    const std::string from_url = "url(#" + id + ")";
    const std::string to_url = "url(#" + to + ")";
    for (std::size_t p = s.find(from_url); p != std::string::npos; p = s.find(from_url, p + to_url.size())) {
      s.replace(p, from_url.size(), to_url);
    }
  }
  return s;
}

}  // namespace locbench::reports
