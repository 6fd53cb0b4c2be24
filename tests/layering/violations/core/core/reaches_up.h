#pragma once
// A fixture for the layering check: core that reaches up into reports/.
#include "reports/report.h"
