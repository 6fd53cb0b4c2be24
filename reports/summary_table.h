#pragma once
// The short plain-text table printed on the terminal after a run.
#include <string>
#include <vector>

#include "reports/report.h"

namespace locbench::reports {

std::string summary_table(const std::vector<Report>& reports);

}  // namespace locbench::reports
