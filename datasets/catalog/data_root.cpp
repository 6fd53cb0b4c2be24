#include "datasets/catalog/data_root.h"

#include <cstdlib>

namespace locbench::catalog {

std::filesystem::path data_root() {
  if (const char* env = std::getenv("LOCBENCH_DATA"); env != nullptr && *env != '\0') {
    return env;
  }
  return std::filesystem::path("..") / "shared" / "datasets";
}

}  // namespace locbench::catalog
