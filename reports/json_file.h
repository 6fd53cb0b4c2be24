#pragma once
// The reports' name for the one JSON file reader (algorithms/core/json_file.h).
#include "algorithms/core/json_file.h"

namespace locbench::reports {

using locbench::parse_json_text;
using locbench::read_json_file;

}  // namespace locbench::reports
