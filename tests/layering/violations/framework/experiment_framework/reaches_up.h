#pragma once
// A fixture for the layering check: the experiment framework reaching into an algorithm.
#include "algorithms/laser/eap_matcher.h"
