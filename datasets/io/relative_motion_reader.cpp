#include "datasets/io/relative_motion_reader.h"

#include <array>

#include "core/errors.h"
#include "datasets/io/data_lines.h"
#include "datasets/io/tokenizer.h"

namespace locbench::io {
namespace {

// The rows of a whitespace-separated numeric file with N columns named `names`.
template <std::size_t N>
std::vector<std::array<double, N>> read_rows(LineReader& reader, const std::array<const char*, N>& names) {
  std::vector<std::array<double, N>> rows;
  for_each_numeric_row(reader, names, [&](const std::array<double, N>& v, const FieldContext&) { rows.push_back(v); });
  return rows;
}

constexpr std::array<const char*, 3> kMotionNames = {"dx", "dy", "dtheta"};
constexpr std::array<const char*, 5> kTickNames = {"tick_left", "tick_right", "x", "y", "theta"};

std::vector<RelativeMotionPair> pair_rows(LineReader& odometry, LineReader& reference) {
  const auto a = read_rows(odometry, kMotionNames);
  const auto b = read_rows(reference, kMotionNames);
  if (a.size() != b.size()) {
    throw InputError(reference.source(), 0,
                     std::to_string(b.size()) + " motion rows, but " + odometry.source() + " has " +
                         std::to_string(a.size()) + "; the two files must have the same rows");
  }
  std::vector<RelativeMotionPair> out;
  out.reserve(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    out.push_back({Pose2(a[i][0], a[i][1], a[i][2]), Pose2(b[i][0], b[i][1], b[i][2])});
  }
  return out;
}

std::vector<TickMotion> tick_rows(LineReader& reader) {
  std::vector<TickMotion> out;
  for (const auto& r : read_rows(reader, kTickNames)) {
    out.push_back({r[0], r[1], Pose2(r[2], r[3], r[4])});
  }
  return out;
}

}  // namespace

std::vector<RelativeMotionPair> read_relative_motion_pairs(const std::filesystem::path& odometry_path,
                                                           const std::filesystem::path& reference_path) {
  LineReader odometry(odometry_path);
  LineReader reference(reference_path);
  return pair_rows(odometry, reference);
}

std::vector<RelativeMotionPair> parse_relative_motion_pairs(std::string_view odometry_text,
                                                            const std::string& odometry_name,
                                                            std::string_view reference_text,
                                                            const std::string& reference_name) {
  LineReader odometry(odometry_text, odometry_name);
  LineReader reference(reference_text, reference_name);
  return pair_rows(odometry, reference);
}

std::vector<TickMotion> read_tick_motions(const std::filesystem::path& path) { return read_lines_of(path, tick_rows); }

std::vector<TickMotion> parse_tick_motions(std::string_view text, const std::string& source_name) {
  return read_lines_of(text, source_name, tick_rows);
}

}  // namespace locbench::io
