// A fixture for the layering check: the CLI reaching into an experiment instead of the registry.
#include "benchmarks/experiments/laser/matcher_accuracy.h"
