#pragma once
// Named scenarios reproducing the thesis's experimental set-ups (table in README.md).
#include <string>
#include <vector>

#include "datasets/sim/scenario.h"

namespace locbench::sim {

struct PresetInfo {
  std::string name;
  std::string description;  // one line
};

// All presets, in a fixed order.
std::vector<PresetInfo> preset_list();
// The scenario of a preset; throws UsageError listing the known names for an unknown one.
Scenario preset(const std::string& name);

}  // namespace locbench::sim
