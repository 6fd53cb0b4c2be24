// A fixture for the layering check: a fuzz target reaching up into the CLI.
#include "cli/commands.h"
