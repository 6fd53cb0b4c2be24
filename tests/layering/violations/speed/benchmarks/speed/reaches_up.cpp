// A fixture for the layering check: a speed kernel reaching up into the CLI.
#include "cli/commands.h"
