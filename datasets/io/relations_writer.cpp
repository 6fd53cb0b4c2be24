#include "datasets/io/relations_writer.h"

#include <cmath>
#include <stdexcept>

#include "datasets/io/number_format.h"
#include "datasets/io/text_writer.h"

namespace locbench::io {

std::string format_relations(const std::vector<Relation>& relations) {
  std::string out = "# t1 t2 x y z roll pitch yaw\n";
  for (std::size_t i = 0; i < relations.size(); ++i) {
    const Relation& r = relations[i];
    for (const double v : {r.t1, r.t2, r.delta.x, r.delta.y, r.delta.theta}) {
      if (!std::isfinite(v)) {
        throw std::invalid_argument("write_relations: relation " + std::to_string(i) + " has a non-finite value");
      }
    }
    append_row(out, {r.t1, r.t2, r.delta.x, r.delta.y, 0.0, 0.0, 0.0, r.delta.theta});
  }
  return out;
}

void write_relations(const std::vector<Relation>& relations, const std::filesystem::path& path) {
  write_text_file(path, format_relations(relations));
}

}  // namespace locbench::io
