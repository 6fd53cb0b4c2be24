#include "core/option_fields.h"

#include <fmt/format.h>

namespace locbench {

std::string Range::text() const {
  const bool low = std::isfinite(lo), high = std::isfinite(hi);
  if (!low && !high) return "a finite number";
  if (low && !high) return fmt::format("{} {}", lo_open ? ">" : "≥", lo);
  if (!low && high) return fmt::format("{} {}", hi_open ? "<" : "≤", hi);
  return fmt::format("a number in {}{}, {}{}", lo_open ? "(" : "[", lo, hi, hi_open ? ")" : "]");
}

std::string fields_markdown(const std::vector<FieldDoc>& rows) {
  std::string out = "| key | default | unit | allowed | meaning |\n| --- | --- | --- | --- | --- |\n";
  for (const FieldDoc& r : rows) {
    out += fmt::format("| `{}` | `{}` | {} | {} | {} |\n", r.name, r.default_json, r.unit, r.allowed, r.meaning);
  }
  return out;
}

}  // namespace locbench
