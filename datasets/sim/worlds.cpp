#include "datasets/sim/worlds.h"

#include <cmath>

#include "core/errors.h"
#include "core/json_file.h"
#include "core/json_options.h"

namespace locbench::sim {
namespace {

Segment seg(double x1, double y1, double x2, double y2) {
  return Segment{Eigen::Vector2d(x1, y1), Eigen::Vector2d(x2, y2)};
}

LineMap from_rows(std::string name, const std::vector<Eigen::Vector4d>& rows, const std::string& source) {
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

LineMap random_room(Rng& rng, const RandomRoomOptions& o) {
  if (!(o.min_size > 0.0) || o.max_size < o.min_size || o.boxes < 0 || o.clearance < 0.0) {
    throw UsageError("random_room: need 0 < min_size ≤ max_size, boxes ≥ 0, clearance ≥ 0");
  }
  const double w = rng.uniform(o.min_size, o.max_size);
  const double h = rng.uniform(o.min_size, o.max_size);
  LineMap m;
  m.name = "random_room";
  m.segments = {seg(0, 0, w, 0), seg(w, 0, w, h), seg(w, h, 0, h), seg(0, h, 0, 0)};
  std::vector<Rect> boxes;
  for (int b = 0, attempts = 0; b < o.boxes && attempts < 100 * (o.boxes + 1); ++attempts) {
    const double bw = rng.uniform(0.5, 2.0), bh = rng.uniform(0.5, 2.0);
    const double lo_x = o.clearance, hi_x = w - o.clearance - bw;
    const double lo_y = o.clearance, hi_y = h - o.clearance - bh;
    if (hi_x <= lo_x || hi_y <= lo_y) continue;
    const Rect r{{rng.uniform(lo_x, hi_x), rng.uniform(lo_y, hi_y)}, {}};
    const Rect box{r.min, r.min + Eigen::Vector2d(bw, bh)};
    bool clear = true;
    for (const Rect& q : boxes) {
      if (box.min.x() < q.max.x() + o.clearance && q.min.x() < box.max.x() + o.clearance &&
          box.min.y() < q.max.y() + o.clearance && q.min.y() < box.max.y() + o.clearance) {
        clear = false;
      }
    }
    if (!clear) continue;
    boxes.push_back(box);
    const double x0 = box.min.x(), y0 = box.min.y(), x1 = box.max.x(), y1 = box.max.y();
    for (const Segment& s : {seg(x0, y0, x1, y0), seg(x1, y0, x1, y1), seg(x1, y1, x0, y1), seg(x0, y1, x0, y0)}) {
      m.segments.push_back(s);
    }
    ++b;
  }
  return m;
}

bool in_free_space(const LineMap& room, const Eigen::Vector2d& p, double margin) {
  for (const Segment& s : room.segments) {
    if (distance_to_segment(s, p) < margin) return false;
  }
  // A ray to the right crosses the outer wall once and each box it passes twice, or once when
  // it starts inside that box: the point is free ⇔ the total is odd.
  int crossings = 0;
  for (const Segment& s : room.segments) {
    const Eigen::Vector2d a = s.p1, b = s.p2;
    if ((a.y() > p.y()) != (b.y() > p.y())) {
      const double x = a.x() + (p.y() - a.y()) / (b.y() - a.y()) * (b.x() - a.x());
      if (x > p.x()) ++crossings;
    }
  }
  return crossings % 2 == 1;
}

LineMap tiled_rooms(int count) {
  if (count < 1) throw UsageError("tiled_rooms: count must be ≥ 1");
  const LineMap room = room_world();
  const int k = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(count))));
  LineMap m;
  m.name = "tiled_rooms_" + std::to_string(count);
  m.segments.reserve(room.segments.size() * static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector2d shift(10.0 * (i % k), 10.0 * (i / k));
    for (const Segment& s : room.segments) m.segments.push_back({s.p1 + shift, s.p2 + shift});
  }
  return m;
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
  m.segments = {seg(0, -h, length, -h), seg(length, -h, length, h), seg(length, h, 0, h), seg(0, h, 0, -h)};
  return m;
}

LineMap world_from_json(const nlohmann::json& j, const std::string& source) {
  StrictJsonReader o(j, "", source);
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
    case WorldKind::kNone: return LineMap{"none", {}};
    case WorldKind::kRoom: return room_world();
    case WorldKind::kCorridor: return corridor_world(w.corridor_length, w.corridor_width);
    case WorldKind::kFile: return load_world(w.file);
    case WorldKind::kInline: return from_rows("inline", w.segments, "<scenario world.segments>");
  }
  return {};
}

}  // namespace locbench::sim
