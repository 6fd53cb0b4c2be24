#pragma once
// A fixture for the layering check: a hidden-effects generator reaching up into the diagnosis.
#include "algorithms/diagnosis/diagnosis.h"
