#pragma once
// A fixture for the layering check: an algorithm that reaches up into datasets/.
#include "datasets/catalog/data_root.h"
