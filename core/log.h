#pragma once
// The one in-memory form of any robot data, simulated or real. SI units, times in seconds.
// Readers (datasets/io) and the simulator (datasets/sim) produce it; experiments consume it.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/pose2.h"
#include "core/robot_params.h"
#include "core/scan.h"
#include "core/sensor_data.h"

namespace locbench {

struct Log {
  std::string name;    // short dataset name, e.g. "aces" or "sim/corridor"
  std::string source;  // path it was read from, or "simulated"
  // PARAM records, verbatim (name → value text).
  std::map<std::string, std::string> params;

  std::vector<EncoderReading> encoders;
  std::vector<OdometryReading> odometry;
  std::vector<CompassReading> compass;
  std::vector<LaserReading> laser;
  std::vector<TruePose> truth;
  std::vector<Relation> relations;
  std::vector<LandmarkReading> landmarks;
  // The surveyed landmarks the observations in `landmarks` refer to (empty when the log has none).
  std::vector<MapLandmark> landmark_map;

  // The nominal odometry model declared by the PARAM records robot_meters_per_tick_left,
  // robot_meters_per_tick_right and robot_wheelbase; nullopt if any is missing.
  std::optional<NominalModel> nominal_model() const;
  // First and last timestamp over all records; {0, 0} for an empty log.
  std::pair<double, double> time_span() const;
  std::size_t record_count() const;
};

// The records of `log` with time in [from, to] (relations: both ends inside; landmark
// observations by their time; the landmark map and PARAM records whole). Logs without ODOM or
// ENCODER records (mit-csail) carry their odometry in the FLASER records: their poses are kept,
// without the scans' ranges.
Log restrict_log(const Log& log, double from, double to);

// PARAM names of the nominal model (see datasets/FORMAT.md).
inline constexpr const char* kParamMetersPerTickLeft = "robot_meters_per_tick_left";
inline constexpr const char* kParamMetersPerTickRight = "robot_meters_per_tick_right";
inline constexpr const char* kParamWheelbase = "robot_wheelbase";

}  // namespace locbench
