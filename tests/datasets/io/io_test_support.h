#pragma once
// Helpers for the datasets/io tests: exact Log comparison, gzip files, InputError checks.
#include <gtest/gtest.h>
#include <zlib.h>

#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <string>

#include "core/errors.h"
#include "core/log.h"

namespace locbench::testing {

inline bool same_pose(const Pose2& a, const Pose2& b) { return a.x == b.x && a.y == b.y && a.theta == b.theta; }

// The first difference between two logs' records and params, or "" if they are identical
// (exact floating-point equality). Name and source are not compared.
inline std::string log_difference(const Log& a, const Log& b) {
  std::ostringstream d;
  d.precision(17);
  auto sizes = [&](const char* what, std::size_t x, std::size_t y) {
    if (x != y) d << what << ": " << x << " vs " << y << " records";
    return x == y;
  };
  if (a.params != b.params) {
    d << "params differ:";
    for (const auto& [k, v] : a.params) d << " [" << k << "=" << v << "]";
    d << " vs";
    for (const auto& [k, v] : b.params) d << " [" << k << "=" << v << "]";
    return d.str();
  }
  if (!sizes("encoders", a.encoders.size(), b.encoders.size())) return d.str();
  for (std::size_t i = 0; i < a.encoders.size(); ++i) {
    const auto &x = a.encoders[i], &y = b.encoders[i];
    if (x.t != y.t || x.left != y.left || x.right != y.right) {
      d << "encoder " << i << ": t " << x.t << "/" << y.t << " ticks " << x.left << "," << x.right << " vs " << y.left
        << "," << y.right;
      return d.str();
    }
  }
  if (!sizes("odometry", a.odometry.size(), b.odometry.size())) return d.str();
  for (std::size_t i = 0; i < a.odometry.size(); ++i) {
    const auto &x = a.odometry[i], &y = b.odometry[i];
    if (x.t != y.t || !same_pose(x.pose, y.pose) || x.tv != y.tv || x.rv != y.rv) {
      d << "odometry " << i << " differs (t " << x.t << " vs " << y.t << ")";
      return d.str();
    }
  }
  if (!sizes("compass", a.compass.size(), b.compass.size())) return d.str();
  for (std::size_t i = 0; i < a.compass.size(); ++i) {
    if (a.compass[i].t != b.compass[i].t || a.compass[i].heading != b.compass[i].heading) {
      d << "compass " << i << " differs";
      return d.str();
    }
  }
  if (!sizes("truth", a.truth.size(), b.truth.size())) return d.str();
  for (std::size_t i = 0; i < a.truth.size(); ++i) {
    const auto &x = a.truth[i], &y = b.truth[i];
    if (x.t != y.t || !same_pose(x.pose, y.pose) || !same_pose(x.odom_pose, y.odom_pose)) {
      d << "truth " << i << " differs";
      return d.str();
    }
  }
  if (!sizes("laser", a.laser.size(), b.laser.size())) return d.str();
  for (std::size_t i = 0; i < a.laser.size(); ++i) {
    const auto &x = a.laser[i], &y = b.laser[i];
    if (x.scan.timestamp != y.scan.timestamp || x.scan.ranges != y.scan.ranges || x.scan.bearings != y.scan.bearings ||
        x.scan.max_range != y.scan.max_range || !same_pose(x.scan.sensor_pose, y.scan.sensor_pose) ||
        !same_pose(x.pose, y.pose) || !same_pose(x.odom_pose, y.odom_pose)) {
      d << "laser " << i << " differs (t " << x.scan.timestamp << ", " << x.scan.ranges.size() << " vs "
        << y.scan.ranges.size() << " beams, max range " << x.scan.max_range << " vs " << y.scan.max_range << ")";
      return d.str();
    }
  }
  if (!sizes("relations", a.relations.size(), b.relations.size())) return d.str();
  for (std::size_t i = 0; i < a.relations.size(); ++i) {
    const auto &x = a.relations[i], &y = b.relations[i];
    if (x.t1 != y.t1 || x.t2 != y.t2 || !same_pose(x.delta, y.delta)) {
      d << "relation " << i << " differs";
      return d.str();
    }
  }
  if (!sizes("landmarks", a.landmarks.size(), b.landmarks.size())) return d.str();
  for (std::size_t i = 0; i < a.landmarks.size(); ++i) {
    const auto &x = a.landmarks[i], &y = b.landmarks[i];
    if (x.t != y.t || x.subject != y.subject || x.range != y.range || x.bearing != y.bearing) {
      d << "landmark " << i << " differs";
      return d.str();
    }
  }
  return "";
}

// `data` compressed in the gzip format.
inline std::string gzip(const std::string& data) {
  z_stream zs{};
  if (deflateInit2(&zs, 6, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK) {
    throw std::runtime_error("deflateInit2 failed");
  }
  std::string out(deflateBound(&zs, static_cast<uLong>(data.size())) + 64, '\0');
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  zs.avail_in = static_cast<uInt>(data.size());
  zs.next_out = reinterpret_cast<Bytef*>(out.data());
  zs.avail_out = static_cast<uInt>(out.size());
  const int rc = deflate(&zs, Z_FINISH);
  deflateEnd(&zs);
  if (rc != Z_STREAM_END) throw std::runtime_error("deflate failed");
  out.resize(zs.total_out);
  return out;
}

inline void write_bytes(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream f(path, std::ios::binary);
  f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!f) throw std::runtime_error("cannot write " + path.string());
}

inline std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream f(path, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

// Expects `fn` to throw InputError at `line` (0: not line-based) of a file whose name contains
// `file`, with every one of `parts` in the message.
template <typename F>
::testing::AssertionResult throws_input_error(F&& fn, const std::string& file, std::size_t line,
                                              std::initializer_list<std::string> parts) {
  try {
    fn();
  } catch (const InputError& e) {
    const std::string msg = e.what();
    if (e.file().find(file) == std::string::npos) {
      return ::testing::AssertionFailure() << "file '" << e.file() << "' lacks '" << file << "' in: " << msg;
    }
    if (e.line() != line) {
      return ::testing::AssertionFailure() << "line " << e.line() << ", expected " << line << " in: " << msg;
    }
    const std::string where = line > 0 ? ":" + std::to_string(line) + ": " : ": ";
    if (msg.find(file) == std::string::npos || msg.find(where) == std::string::npos) {
      return ::testing::AssertionFailure() << "message does not start with file:line: " << msg;
    }
    for (const auto& p : parts) {
      if (msg.find(p) == std::string::npos) {
        return ::testing::AssertionFailure() << "message lacks '" << p << "': " << msg;
      }
    }
    return ::testing::AssertionSuccess() << msg;
  } catch (const std::exception& e) {
    return ::testing::AssertionFailure() << "threw another exception: " << e.what();
  }
  return ::testing::AssertionFailure() << "did not throw";
}

}  // namespace locbench::testing
