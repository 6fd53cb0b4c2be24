#pragma once
#include <string>

#include "reports/report.h"

namespace locbench::reports {

// Version, git revision, compiler and flags baked in at build time; host and UTC time now.
Provenance current_provenance(const std::string& command_line);

}  // namespace locbench::reports
