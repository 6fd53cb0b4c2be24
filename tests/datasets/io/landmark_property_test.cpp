// Properties of the plain landmark readers: random valid files (any spacing, comments, blank
// lines, optional σ, plain or written by the writers) parse back to what made them, and random
// byte mutations of a valid file are read or rejected with InputError, never anything else.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <set>

#include "datasets/io/landmark_reader.h"
#include "datasets/io/landmark_writer.h"
#include "datasets/io/number_format.h"
#include "log_generators.h"

namespace locbench::io {
namespace {

using testing::gen_finite;
using testing::gen_range;
using testing::gen_times;

std::vector<MapLandmark> random_map() {
  const auto ids = *rc::gen::container<std::set<int>>(rc::gen::arbitrary<int>());
  std::vector<MapLandmark> map;
  for (int id : ids) {
    MapLandmark m{id, *gen_finite(), *gen_finite(), 0.0, 0.0};
    if (*rc::gen::arbitrary<bool>()) {
      m.sigma_x = *gen_range();
      m.sigma_y = *gen_range();
    }
    map.push_back(m);
  }
  return map;
}

std::vector<LandmarkReading> random_observations() {
  std::vector<LandmarkReading> out;
  for (double t : *gen_times(30)) {
    out.push_back({t, *rc::gen::arbitrary<int>(), *gen_range(), *gen_finite()});
  }
  return out;
}

// Fields joined by random runs of spaces and tabs, with random comment and blank lines between.
std::string random_layout(const std::vector<std::vector<std::string>>& rows) {
  static const std::vector<std::string> kBetweenLines = {"# comment 1 2 3\n", "\n", "  \t\n"};
  static const std::vector<std::string> kSpaces = {" ", "\t", "  ", " \t "};
  static const std::vector<std::string> kEnds = {"\n", "\r\n", " \n"};
  std::string text;
  for (const auto& row : rows) {
    if (*rc::gen::inRange(0, 4) == 0) text += *rc::gen::elementOf(kBetweenLines);
    for (const std::string& field : row) {
      text += *rc::gen::elementOf(kSpaces) + field;
    }
    text += *rc::gen::elementOf(kEnds);
  }
  if (text.empty()) text = "# nothing\n";
  return text;
}

std::string num(double v) { return number_text(v); }

bool same(const MapLandmark& a, const MapLandmark& b) {
  return a.id == b.id && a.x == b.x && a.y == b.y && a.sigma_x == b.sigma_x && a.sigma_y == b.sigma_y;
}
bool same(const LandmarkReading& a, const LandmarkReading& b) {
  return a.t == b.t && a.subject == b.subject && a.range == b.range && a.bearing == b.bearing;
}

RC_GTEST_PROP(LandmarkFormats, ARandomValidMapParsesBackEqual, ()) {
  const auto map = random_map();
  std::vector<std::vector<std::string>> rows;
  for (const MapLandmark& m : map) {
    std::vector<std::string> row = {std::to_string(m.id), num(m.x), num(m.y)};
    if (m.sigma_x != 0.0 || m.sigma_y != 0.0 || *rc::gen::arbitrary<bool>()) {
      row.push_back(num(m.sigma_x));
      row.push_back(num(m.sigma_y));
    }
    rows.push_back(row);
  }
  for (const std::string& text : {random_layout(rows), format_landmark_map(map)}) {
    const auto back = parse_landmark_map(text, "map.txt");
    RC_ASSERT(back.size() == map.size());
    for (std::size_t i = 0; i < map.size(); ++i) RC_ASSERT(same(back[i], map[i]));
  }
}

RC_GTEST_PROP(LandmarkFormats, RandomValidObservationsParseBackEqual, ()) {
  const auto obs = random_observations();
  std::vector<std::vector<std::string>> rows;
  for (const LandmarkReading& r : obs) {
    rows.push_back({num(r.t), std::to_string(r.subject), num(r.range), num(r.bearing)});
  }
  for (const std::string& text : {random_layout(rows), format_landmark_observations(obs)}) {
    const auto back = parse_landmark_observations(text, "obs.txt");
    RC_ASSERT(back.readings.size() == obs.size());
    RC_ASSERT(back.lines.size() == obs.size());
    for (std::size_t i = 0; i < obs.size(); ++i) RC_ASSERT(same(back.readings[i], obs[i]));
  }
}

// 1–8 random byte edits: replace, insert or delete one byte, or cut the text.
std::string mutate_bytes(std::string text) {
  const int edits = *rc::gen::inRange(1, 9);
  for (int e = 0; e < edits; ++e) {
    const std::size_t i = *rc::gen::inRange<std::size_t>(0, text.size() + 1);
    const char c = *rc::gen::oneOf(rc::gen::arbitrary<char>(), rc::gen::element(' ', '\n', '#', '-', '.', 'e', '9'));
    switch (*rc::gen::inRange(0, 4)) {
      case 0:
        if (i < text.size()) text[i] = c;
        break;
      case 1: text.insert(text.begin() + static_cast<std::ptrdiff_t>(i), c); break;
      case 2:
        if (i < text.size()) text.erase(i, 1);
        break;
      default: text.resize(i); break;
    }
  }
  return text;
}

RC_GTEST_PROP(LandmarkFormats, MutatedMapsAreReadOrRejectedWithInputError, ()) {
  const std::string text = mutate_bytes(format_landmark_map(random_map()) + "6 0.58831396 -4.28264845 4.5e-05 0\n");
  testing::reads_or_rejects([&] { parse_landmark_map(text, "map.txt"); });
}

RC_GTEST_PROP(LandmarkFormats, MutatedObservationsAreReadOrRejectedWithInputError, ()) {
  const std::string text =
      mutate_bytes("1248444189.599 14 3.787 -0.257\n1248444189.828 61 6.6 -0.022\n" +
                   format_landmark_observations({{1248444190.0, 6, 1.0, 0.5}, {1248444191.0, 7, 0.0, -3.0}}));
  testing::reads_or_rejects([&] {
    const auto obs = parse_landmark_observations(text, "obs.txt");
    Log log;
    log.odometry.push_back({1248444189.0, Pose2(), 0.0, 0.0});
    attach_landmarks(log, parse_landmark_map("6 0 0\n7 1 1\n14 2 2\n61 3 3\n", "map.txt"), obs, "map.txt", "obs.txt");
  });
}

}  // namespace
}  // namespace locbench::io
