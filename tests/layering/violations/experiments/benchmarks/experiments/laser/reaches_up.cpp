// A fixture for the layering check: an experiment reaching up into the CLI.
#include "cli/commands.h"
