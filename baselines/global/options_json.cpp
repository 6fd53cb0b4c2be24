// JSON to/from of the global-localization options (strict: unknown keys and wrong types throw
// UsageError naming the key; values in SI units, angles in radians). The fields are stated in
// options_fields.h.
#include "baselines/global/options_fields.h"

namespace locbench::baselines::global {

LOCBENCH_OPTIONS_JSON(OdometryMotionOptions)
LOCBENCH_OPTIONS_JSON(LikelihoodFieldOptions)
LOCBENCH_OPTIONS_JSON(MclOptions)
LOCBENCH_OPTIONS_JSON(GridMarkovOptions)

}  // namespace locbench::baselines::global
