#pragma once
// A fixture for the layering check: a baseline reaching into datasets/.
#include "datasets/io/carmen_reader.h"
