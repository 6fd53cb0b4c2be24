#pragma once
// The findings a reader wants first: for each published table with a stated tolerance, whether
// our measurement reproduces it, computed from the numbers in the report (never written by hand).
#include <string>
#include <vector>

#include "reports/report.h"

namespace locbench::reports {

enum class Verdict {
  kReproduced,     // every row with both figures within tolerance
  kNotReproduced,  // some row outside tolerance and not explained by an independent check
  kThesisWrong,    // every row outside tolerance has a check agreeing with ours, not with the thesis
  kNoVerdict,      // no tolerance stated, or no row with both figures
};
std::string to_string(Verdict v);  // "reproduced", "not reproduced", "the thesis is wrong", "no verdict"

// One row's tolerance: its own when given, else max(tolerance, relative_tolerance·|published|)
// (0 when neither is given).
double row_tolerance(const PublishedComparison& c, const PublishedRow& row);

struct TableFinding {
  Verdict verdict = Verdict::kNoVerdict;
  std::size_t compared = 0;      // rows with both figures
  std::size_t within = 0;        // of those, within tolerance
  std::size_t thesis_wrong = 0;  // outside tolerance, our figure confirmed by the row's check
  std::string reason;            // one line, with the numbers
};
// Row verdicts: |ours − published| ≤ tolerance → reproduced; else a row whose check lies within
// tolerance of ours and outside tolerance of the published figure → the thesis is wrong; else not
// reproduced. The table: reproduced when all rows are, the thesis is wrong when every row outside
// tolerance is, else not reproduced; the reason names the worst row.
TableFinding table_finding(const PublishedComparison& c);

// The rule for runs not paired with the thesis's: the per-run rows leave the verdict (compared =
// false), and rows whose label starts with "mean" are reproduced within one sample standard
// deviation of the published runs (the scatter between the thesis's own repetitions), which
// becomes the table's tolerance and its basis.
void compare_means_only(PublishedComparison& c, const std::vector<double>& published_runs);

}  // namespace locbench::reports
