// A fixture for the layering check: a reader that reaches up into reports/.
#include "reports/finish_report.h"
