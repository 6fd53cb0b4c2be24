#pragma once
// The reports' name for the one JSON file reader (core/json_file.h).
#include "core/json_file.h"

namespace locbench::reports {

using locbench::parse_json_text;
using locbench::read_json_file;

}  // namespace locbench::reports
