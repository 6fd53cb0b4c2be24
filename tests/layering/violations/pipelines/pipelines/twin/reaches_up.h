#pragma once
// A fixture for the layering check: a pipeline reaching up into an experiment.
#include "benchmarks/experiments/diagnosis/sim_to_real.h"
