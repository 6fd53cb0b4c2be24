// A fixture for the layering check: the simulator reaching into the catalog.
#include "datasets/catalog/data_root.h"
