#include "baselines/laser/options_json.h"

#include "baselines/laser/options_fields.h"

namespace locbench::baselines::laser {

// Each struct's fields are in options_fields.h; from_json validates (nested structs on reading).
LOCBENCH_OPTIONS_JSON(BreakpointOptions)
LOCBENCH_OPTIONS_JSON(LineAcceptance)
LOCBENCH_OPTIONS_JSON(SplitAndMergeOptions)
LOCBENCH_OPTIONS_JSON(AgglomerativeOptions)
LOCBENCH_OPTIONS_JSON(RwhtOptions)
LOCBENCH_OPTIONS_JSON(LineMatchOptions)
LOCBENCH_OPTIONS_JSON(SplitAndMergeMatcherOptions)
LOCBENCH_OPTIONS_JSON(AgglomerativeMatcherOptions)
LOCBENCH_OPTIONS_JSON(RwhtMatcherOptions)

}  // namespace locbench::baselines::laser
