#include "datasets/sim/worlds.h"

#include "algorithms/core/errors.h"
#include "datasets/sim/json_fields.h"

namespace locbench::sim {
namespace {

Segment seg(double x1, double y1, double x2, double y2) {
  return Segment{Eigen::Vector2d(x1, y1), Eigen::Vector2d(x2, y2)};
}

LineMap from_rows(std::string name, const std::vector<Eigen::Vector4d>& rows,
                  const std::string& source) {
  LineMap m;
  m.name = std::move(name);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& r = rows[i];
    if (!r.allFinite()) {
      throw InputError(source, 0, "segments[" + std::to_string(i) + "]: non-finite coordinate");
    }
    Segment s = seg(r[0], r[1], r[2], r[3]);
    if (s.length() <= 0.0) {
      throw InputError(source, 0, "segments[" + std::to_string(i) + "]: zero-length segment");
    }
    m.segments.push_back(s);
  }
  return m;
}

}  // namespace

std::vector<Rect> room_obstacles() {
  return {
      {{5.0, 0.0}, {7.0, 1.0}},  // A: 2 × 1 m against the bottom wall
      {{4.0, 4.0}, {6.0, 6.0}},  // B: 2 × 2 m free-standing
      {{0.0, 5.0}, {1.0, 7.0}},  // C: 1 × 2 m against the left wall
  };
}

LineMap room_world() {
  const double s = kRoomSize;
  LineMap m;
  m.name = "room";
  m.segments = {
      // walls, counter-clockwise from the origin
      seg(0, 0, s, 0),
      seg(s, 0, s, s),
      seg(s, s, 0, s),
      seg(0, s, 0, 0),
      // A: left, top, right faces
      seg(5, 0, 5, 1),
      seg(5, 1, 7, 1),
      seg(7, 1, 7, 0),
      // B: all four faces
      seg(4, 4, 6, 4),
      seg(6, 4, 6, 6),
      seg(6, 6, 4, 6),
      seg(4, 6, 4, 4),
      // C: bottom, right, top faces
      seg(0, 5, 1, 5),
      seg(1, 5, 1, 7),
      seg(1, 7, 0, 7),
  };
  return m;
}

LineMap corridor_world(double length, double width) {
  const double h = 0.5 * width;
  LineMap m;
  m.name = "corridor";
  m.segments = {seg(0, -h, length, -h), seg(length, -h, length, h), seg(length, h, 0, h),
                seg(0, h, 0, -h)};
  return m;
}

LineMap world_from_json(const nlohmann::json& j, const std::string& source) {
  JsonObject o(j, "", source);
  std::string name = "world";
  o.read("name", name);
  const auto* segs = o.raw("segments");
  if (!segs) throw InputError(source, 0, "segments: missing");
  if (!segs->is_array()) {
    throw InputError(source, 0, "segments: expected an array, found " + json_type_name(*segs));
  }
  o.finish();
  std::vector<Eigen::Vector4d> rows;
  for (std::size_t i = 0; i < segs->size(); ++i) {
    Eigen::Vector4d r;
    read_numbers((*segs)[i], r.data(), 4, "segments[" + std::to_string(i) + "]", source);
    rows.push_back(r);
  }
  return from_rows(name, rows, source);
}

LineMap load_world(const std::filesystem::path& path) {
  return world_from_json(read_json_file(path.string()), path.string());
}

LineMap build_world(const WorldConfig& w) {
  switch (w.kind) {
    case WorldKind::kNone:
      return LineMap{"none", {}};
    case WorldKind::kRoom:
      return room_world();
    case WorldKind::kCorridor:
      return corridor_world(w.corridor_length, w.corridor_width);
    case WorldKind::kFile:
      return load_world(w.file);
    case WorldKind::kInline:
      return from_rows("inline", w.segments, "<scenario world.segments>");
  }
  return {};
}

}  // namespace locbench::sim
