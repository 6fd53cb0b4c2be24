#pragma once
// Reader of one robot of a UTIAS MRCLAM dataset folder (Leung et al., IJRR 2011).
#include <filesystem>
#include <set>
#include <string_view>

#include "core/log.h"

namespace locbench::io {

// PARAM-style entries the reader stores in Log::params.
inline constexpr std::string_view kParamMrclamRobot = "mrclam_robot";  // robot number
// "subject" when measurements were mapped from barcodes to subject numbers through
// Barcodes.dat, "barcode" when that file is absent and the raw barcodes are kept.
inline constexpr std::string_view kParamMrclamMeasurementIds = "mrclam_measurement_ids";
// Number of measurements dropped because their barcode is not in Barcodes.dat (camera misreads;
// more than 1% of a file's measurements is an InputError).
inline constexpr std::string_view kParamMrclamUnknownBarcodes = "mrclam_unknown_barcode_measurements";
// The subjects that are robots, "1,2,3,4,5": every N with a RobotN_Odometry.dat[.gz] in the
// folder. Their measurements stay in Log::landmarks; an experiment that wants landmarks only
// leaves them out (mrclam_robot_subjects below) and counts them.
inline constexpr std::string_view kParamMrclamRobotSubjects = "mrclam_robot_subjects";

// The robot subjects a log names in kParamMrclamRobotSubjects; empty without the param.
std::set<int> mrclam_robot_subjects(const Log& log);

// Reads RobotN_Odometry.dat, RobotN_Groundtruth.dat and RobotN_Measurement.dat (each plain or
// .gz, all required; Barcodes.dat optional) from `folder`:
// - odometry: time, v, ω → OdometryReading{t, pose, tv = v, rv = ω}; the pose is dead reckoned
//   from the velocities (each held over the interval to the next record, midpoint rule),
//   starting at the ground-truth pose at the first odometry time (interpolated; the nearest
//   ground-truth pose when that time is outside the ground truth; the origin without any);
// - ground truth: time, x, y, θ → TruePose (odom_pose left at zero);
// - measurements: time, barcode, range, bearing → LandmarkReading with the subject number;
// - Landmark_Groundtruth.dat (optional; read_landmark_map): subject x y σx σy → Log::landmark_map.
// With a landmark map, a measurement of a subject that is neither a map landmark nor a robot is
// an InputError (and so is a map without Barcodes.dat). A measurement before the first odometry
// record is an InputError, and so are unknown barcodes in more than 1% of the measurements.
// Log::name is e.g. "mrclam6/robot1" for folder MRCLAM_Dataset6, Log::source "<folder>#robot1".
// Throws InputError for a missing file, malformed lines or times going backwards.
Log read_mrclam_robot(const std::filesystem::path& folder, int robot);

}  // namespace locbench::io
