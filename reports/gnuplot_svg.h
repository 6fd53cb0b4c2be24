#pragma once
// Runs Debian's gnuplot (gnuplot-nox) to draw charts as SVG for the HTML report.
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace locbench::reports {

// $LOCBENCH_GNUPLOT when set, else `gnuplot` on $PATH; nullopt when there is none.
std::optional<std::filesystem::path> find_gnuplot();

// Runs `gnuplot` on `script` (which sets the svg terminal and plots to stdout) and returns the
// SVG it wrote; std::runtime_error with gnuplot's messages when it fails.
std::string run_gnuplot(const std::filesystem::path& gnuplot, const std::string& script);

// Runs one `gnuplot` on all `scripts` (each of the form above) and returns their SVGs in order:
// each script is preceded by `reset` and `set output` to its own file, so one process draws the
// page. std::runtime_error-derived InputError with gnuplot's messages when it fails.
std::vector<std::string> run_gnuplot_batch(const std::filesystem::path& gnuplot,
                                           const std::vector<std::string>& scripts);

// The values of the id="…" and id='…' attributes of `svg`, as the regular expression
// \bid=(['"])([^'"]+)\1 finds them: an "id=" after a letter, digit or '_' (as in "grid=") is not
// one, and matches do not overlap.
std::set<std::string> element_ids(const std::string& svg);

// An SVG document made fit to inline into HTML: the XML declaration dropped and every id made
// unique with `prefix` (references included), so several charts can share one page.
std::string inline_svg(const std::string& svg, const std::string& prefix);

}  // namespace locbench::reports
