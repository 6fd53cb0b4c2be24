#include "core/scan.h"

namespace locbench {

std::vector<double> even_bearings(std::size_t count, double first, double last) {
  std::vector<double> b(count);
  if (count == 1) {
    b[0] = first;
    return b;
  }
  const double step = (last - first) / static_cast<double>(count - 1);
  for (std::size_t i = 0; i < count; ++i) b[i] = first + step * static_cast<double>(i);
  return b;
}

}  // namespace locbench
