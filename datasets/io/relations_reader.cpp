#include "datasets/io/relations_reader.h"

#include <array>
#include <span>

#include "datasets/io/line_reader.h"
#include "datasets/io/tokenizer.h"

namespace locbench {
namespace {

std::vector<Relation> read_lines(LineReader& reader) {
  static constexpr std::array<const char*, 8> kNames = {"t1", "t2",   "x",     "y",
                                                        "z",  "roll", "pitch", "yaw"};
  std::vector<Relation> out;
  std::vector<std::string_view> tokens;
  std::string_view line;
  while (reader.next(line)) {
    split_fields(line, tokens);
    if (tokens.empty() || tokens[0][0] == '#') continue;
    const FieldContext ctx{reader.source(), reader.line_number(), {}};
    expect_field_count(tokens, kNames.size(), ctx);
    std::array<double, 8> v{};
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = parse_finite(tokens[i], kNames[i], ctx);
    out.push_back({v[0], v[1], Pose2(v[2], v[3], v[7])});
  }
  return out;
}

}  // namespace

std::vector<Relation> read_relations(const std::filesystem::path& path) {
  LineReader reader(path);
  return read_lines(reader);
}

std::vector<Relation> parse_relations(std::string_view text, const std::string& source_name) {
  LineReader reader(text, source_name);
  return read_lines(reader);
}

}  // namespace locbench
