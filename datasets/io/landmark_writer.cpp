#include "datasets/io/landmark_writer.h"

#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "datasets/io/number_format.h"
#include "datasets/io/text_writer.h"

namespace locbench::io {
namespace {

void append_values(std::string& out, std::int64_t id, std::initializer_list<double> values) {
  append_number(out, id);
  for (double v : values) {
    if (!std::isfinite(v)) throw std::invalid_argument("landmark file: non-finite number for id " + std::to_string(id));
    out += ' ';
    append_number(out, v);
  }
  out += '\n';
}

}  // namespace

std::string format_landmark_map(const std::vector<MapLandmark>& map) {
  std::string out = "# landmark map: id x y sigma_x sigma_y [m]\n";
  for (const MapLandmark& m : map) {
    if (!(m.sigma_x >= 0.0) || !(m.sigma_y >= 0.0)) {
      throw std::invalid_argument("landmark map: negative sigma for id " + std::to_string(m.id));
    }
    append_values(out, m.id, {m.x, m.y, m.sigma_x, m.sigma_y});
  }
  return out;
}

std::string format_landmark_observations(const std::vector<LandmarkReading>& observations) {
  std::string out = "# landmark observations: t [s] id range [m] bearing [rad]\n";
  for (std::size_t i = 0; i < observations.size(); ++i) {
    const LandmarkReading& r = observations[i];
    if (!std::isfinite(r.t) || !std::isfinite(r.range) || !std::isfinite(r.bearing)) {
      throw std::invalid_argument("landmark observations: non-finite number in observation " + std::to_string(i));
    }
    if (r.range < 0.0) throw std::invalid_argument("landmark observations: negative range");
    if (i > 0 && r.t < observations[i - 1].t) throw std::invalid_argument("landmark observations: time goes back");
    append_number(out, r.t);
    out += ' ';
    append_number(out, static_cast<std::int64_t>(r.subject));
    out += ' ';
    append_number(out, r.range);
    out += ' ';
    append_number(out, r.bearing);
    out += '\n';
  }
  return out;
}

void write_landmark_map(const std::vector<MapLandmark>& map, const std::filesystem::path& path) {
  write_text_file(path, format_landmark_map(map));
}

void write_landmark_observations(const std::vector<LandmarkReading>& observations, const std::filesystem::path& path) {
  write_text_file(path, format_landmark_observations(observations));
}

}  // namespace locbench::io
