#include "datasets/io/relations_reader.h"

#include <array>

#include "datasets/io/data_lines.h"

namespace locbench::io {
namespace {

std::vector<Relation> read_relation_lines(LineReader& reader) {
  static constexpr std::array<const char*, 8> kNames = {"t1", "t2", "x", "y", "z", "roll", "pitch", "yaw"};
  std::vector<Relation> out;
  for_each_numeric_row(reader, kNames, [&](const std::array<double, 8>& v, const FieldContext&) {
    out.push_back({v[0], v[1], Pose2(v[2], v[3], v[7])});
  });
  return out;
}

}  // namespace

std::vector<Relation> read_relations(const std::filesystem::path& path) {
  return read_lines_of(path, read_relation_lines);
}

std::vector<Relation> parse_relations(std::string_view text, const std::string& source_name) {
  return read_lines_of(text, source_name, read_relation_lines);
}

}  // namespace locbench::io
