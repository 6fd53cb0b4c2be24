#pragma once
// A fixture for the layering check: the catalog reaching up into an algorithm.
#include "algorithms/calibration/calibration_data.h"
