#pragma once
// A fixture for the layering check: reports/ that knows an algorithm.
#include "algorithms/diagnosis/diagnosis.h"
