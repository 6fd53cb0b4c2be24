#pragma once
#include <string>

#include "reports/report.h"

namespace locbench::reports {

// Version, git revision, compiler and flags baked in at build time; host and UTC time now; this
// invocation's run id.
Provenance current_provenance(const std::string& command_line);

// This process's run id, made once ("20261127T041200Z-12345-9f3a0c1e": UTC time, process id and
// 32 random bits) and the same in every report the invocation writes.
const std::string& invocation_run_id();

}  // namespace locbench::reports
