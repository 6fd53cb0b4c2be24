#pragma once
// rapidcheck generators of random Logs that the CARMEN format can hold exactly.
#include <rapidcheck.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <exception>
#include <limits>
#include <string>
#include <vector>

#include "core/errors.h"
#include "core/log.h"
#include "datasets/io/carmen_laser.h"
#include "datasets/io/number_format.h"

namespace locbench::testing {

// Finite doubles of every magnitude, plus realistic timestamps and small round values.
inline rc::Gen<double> gen_finite() {
  return rc::gen::oneOf(rc::gen::suchThat(rc::gen::arbitrary<double>(), [](double v) { return std::isfinite(v); }),
                        rc::gen::map(rc::gen::inRange<std::int64_t>(-2'000'000'000'000'000, 2'000'000'000'000'000),
                                     [](std::int64_t k) { return static_cast<double>(k) * 1e-6; }),
                        rc::gen::map(rc::gen::inRange(-1000, 1000), [](int k) { return k * 0.001; }),
                        rc::gen::element(0.0, -0.0, 1e-300, 4.9e-324, -1.7976931348623157e308, 0.1, 1.0 / 3.0));
}

// Non-decreasing timestamps, with repeats.
inline rc::Gen<std::vector<double>> gen_times(int max_count) {
  return rc::gen::map(
      rc::gen::container<std::vector<double>>(static_cast<std::size_t>(*rc::gen::inRange(0, max_count + 1)),
                                              rc::gen::oneOf(gen_finite(), rc::gen::just(1.0))),
      [](std::vector<double> v) {
        std::sort(v.begin(), v.end());
        return v;
      });
}

// Poses with θ in [-π, π) as Pose2 keeps it.
inline rc::Gen<Pose2> gen_pose() {
  return rc::gen::suchThat(rc::gen::apply([](double x, double y, double th) { return Pose2(x, y, th); }, gen_finite(),
                                          gen_finite(), gen_finite()),
                           [](const Pose2& p) { return p.theta >= -kPi && p.theta < kPi; });
}

inline rc::Gen<double> gen_range() {
  return rc::gen::oneOf(rc::gen::map(gen_finite(), [](double v) { return std::abs(v); }),
                        rc::gen::element(0.0, 81.9, 81.91, 50.0, 4.5));
}

inline rc::Gen<std::string> gen_token(const char* alphabet) {
  const std::string chars(alphabet);
  return rc::gen::nonEmpty(rc::gen::container<std::string>(
      rc::gen::map(rc::gen::inRange<std::size_t>(0, chars.size()), [chars](std::size_t i) { return chars[i]; })));
}

// A Log that write_carmen_log can store and read back unchanged.
inline Log random_carmen_log() {
  Log log;
  const int n_params = *rc::gen::inRange(0, 4);
  for (int i = 0; i < n_params; ++i) {
    log.params[*gen_token("abcdefghijklmnopqrstuvwxyz_")] = *gen_token("abcxyzABC0123456789.-+_#:/!~\"'");
  }
  // Laser setup: the SICK default, or PARAM records declaring another max range / mounting.
  double max_range = locbench::io::kDefaultFlaserMaxRange;
  Pose2 sensor;
  if (*rc::gen::arbitrary<bool>()) {
    max_range = *rc::gen::suchThat(rc::gen::map(gen_finite(), [](double v) { return std::abs(v); }),
                                   [](double v) { return v > 0.0; });
    sensor = *gen_pose();
    std::string v;
    locbench::io::append_number(v, max_range);
    log.params[std::string(*rc::gen::element(locbench::io::kParamLaserMaxRange, locbench::io::kParamRobotLaserMax))] =
        v;
    for (const auto& [name, value] : {std::pair{locbench::io::kParamLaserOffset, sensor.x},
                                      std::pair{locbench::io::kParamLaserSideOffset, sensor.y},
                                      std::pair{locbench::io::kParamLaserAngularOffset, sensor.theta}}) {
      std::string text;
      locbench::io::append_number(text, value);
      log.params[std::string(name)] = text;
    }
  }

  const auto gen_ticks =
      rc::gen::oneOf(rc::gen::arbitrary<std::int64_t>(),
                     rc::gen::element(std::numeric_limits<std::int64_t>::min(),
                                      std::numeric_limits<std::int64_t>::max(), std::int64_t{0}, std::int64_t{-1}));
  for (const double t : *gen_times(8)) log.encoders.push_back({t, *gen_ticks, *gen_ticks});
  for (const double t : *gen_times(8)) {
    log.odometry.push_back({t, *gen_pose(), *gen_finite(), *gen_finite()});
  }
  for (const double t : *gen_times(5)) log.compass.push_back({t, *gen_finite()});
  for (const double t : *gen_times(5)) log.truth.push_back({t, *gen_pose(), *gen_pose()});
  for (const double t : *gen_times(4)) {
    LaserReading r;
    const auto n = static_cast<std::size_t>(*rc::gen::oneOf(rc::gen::element(180, 181, 361), rc::gen::inRange(1, 400)));
    r.scan.timestamp = t;
    r.scan.ranges = *rc::gen::container<std::vector<double>>(n, gen_range());
    r.scan.bearings = locbench::io::flaser_bearings(n);
    r.scan.max_range = max_range;
    r.scan.sensor_pose = sensor;
    r.pose = *gen_pose();
    r.odom_pose = *gen_pose();
    log.laser.push_back(std::move(r));
  }
  return log;
}

// A fuzzed input is read, or rejected with InputError; any other exception fails the property.
template <class Read>
void reads_or_rejects(Read&& read) {
  try {
    read();
    RC_TAG("read");
  } catch (const InputError&) {
    RC_TAG("rejected");
  } catch (const std::exception& e) {
    RC_FAIL(std::string("threw something other than InputError: ") + e.what());
  } catch (...) {
    RC_FAIL("threw a non-exception");
  }
}

}  // namespace locbench::testing
