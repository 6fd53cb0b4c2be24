#pragma once
// Transitional forwarding header: the old name of skewness_kurtosis_normality.h. It stays only
// while benchmarks/experiments/slip_normality.cpp and algorithms/diagnosis/histogram_diagnosis.cpp
// (edited on other branches) include it; delete it once they include the new name.
#include "algorithms/slip/skewness_kurtosis_normality.h"
