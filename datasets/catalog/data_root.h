#pragma once
// Where the real datasets live: $LOCBENCH_DATA, else ../shared/datasets (relative to the
// working directory, i.e. beside the project checkout when run from its top).
#include <filesystem>

namespace locbench::catalog {

std::filesystem::path data_root();

}  // namespace locbench::catalog
