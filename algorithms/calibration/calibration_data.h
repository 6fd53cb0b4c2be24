#pragma once
// The one input form of the maximum-likelihood odometry calibration (ml_calibration.h): samples,
// each an interval with the odometry's measurements over it and a reference displacement over
// the same interval, plus builders from every kind of data locbench reads. The model that maps
// the measurements to a displacement, and its parameters per input kind, are in
// calibration_model.h; ML_CALIBRATION.md explains both.
#include <Eigen/Core>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/calibration_records.h"
#include "core/log.h"
#include "core/pose2.h"
#include "core/robot_params.h"

namespace locbench::calibration {

// What the odometry measured; decides the parameterisation (calibration_model.h).
enum class OdometryInputKind {
  // Encoder count increments (left, right). Parameters left_scale, right_scale (multiplying the
  // nominal metres per tick) and wheelbase [m]: U = scale · c_nominal · ticks, eq. 1.1–1.2.
  kWheelTicks,
  // Wheel rotation angles (left, right) [rad]. Parameters r_L, r_R (wheel radii) [m] and b
  // (axle length) [m]: U = r · angle. Censi et al.'s parameterisation.
  kWheelAngles,
  // Odometry displacements reduced to (arc length d [m], rotation θ [rad]). Parameters
  // translation_scale, rotation_scale, rotation_per_distance [rad/m]:
  // d' = translation_scale · d, θ' = rotation_scale · θ + rotation_per_distance · d.
  kBodyIncrements,
  // Integrals of logged velocities (∫tv dt [m], ∫rv dt [rad]) over dt. Parameters tv_scale,
  // rv_scale, rv_bias [rad/s]: d' = tv_scale · ∫tv dt, θ' = rv_scale · ∫rv dt + rv_bias · dt.
  kVelocityIntegrals,
};

// One odometry measurement inside a sample, in the units of the data's kind: (left, right)
// ticks or wheel angles, or (distance, rotation). `dt` is its duration [s] (0 when unknown).
struct OdometryIncrement {
  double first = 0.0;
  double second = 0.0;
  double dt = 0.0;
};

struct CalibrationSample {
  // The odometry over the interval, in time order. Each increment is integrated as a circular
  // arc (constant velocities over it), as Censi et al. do.
  std::vector<OdometryIncrement> increments;
  // Displacement over the interval in the frame at its start: of the robot, or of the sensor
  // when CalibrationData::sensor_reference is true (e.g. a scan matcher's output).
  Pose2 reference;
  double t_start = std::numeric_limits<double>::quiet_NaN();  // [s]; NaN when unknown
  double t_end = std::numeric_limits<double>::quiet_NaN();
};

// Every number of the reference and of the increments is finite (the times may be NaN).
bool is_finite(const CalibrationSample& s);

struct CalibrationData {
  std::string source;  // what the samples were built from, for reports
  OdometryInputKind kind = OdometryInputKind::kWheelTicks;
  // kWheelTicks: nominal metres per tick c_L, c_R (the ticks' unit); unused otherwise.
  double meters_per_tick_left = 1.0;
  double meters_per_tick_right = 1.0;
  // kWheelTicks: the ticks are whole encoder counts, so each sample's travel carries the
  // quantization error of eq. 4.12–4.21 (set by calibration_data_from_encoders; false for files
  // holding fractional "ticks").
  bool quantized_ticks = false;
  // The uncalibrated values of the three odometry parameters of `kind`, in the order of
  // odometry_parameter_names(kind): e.g. (1, 1, B_nominal) for ticks, (1, 1, 0) for the body
  // and velocity kinds.
  Eigen::Vector3d nominal = Eigen::Vector3d(1.0, 1.0, 0.0);
  // True when the references are displacements of a sensor mounted at an unknown (or given)
  // pose ℓ on the robot: reference = ℓ⁻¹ ∘ robot displacement ∘ ℓ (Censi et al. eq. 3).
  bool sensor_reference = false;
  Pose2 nominal_sensor_pose;  // prior guess of ℓ, e.g. from PARAM records
  std::vector<CalibrationSample> samples;
};

// How a time-stamped log is cut into samples. A sample closes at the first odometry record where
// the nominal odometry since its start has travelled `max_distance`, or turned `max_rotation`,
// or `max_duration` has passed — whichever comes first.
struct SampleIntervalOptions {
  double max_distance = 0.5;    // [m]
  double max_rotation = 0.5;    // [rad]
  double max_duration = 5.0;    // [s]
  bool skip_stationary = true;  // drop samples over which the odometry did not move
  // Drop samples where consecutive reference (ground-truth) records inside or around the interval
  // are further apart than this [s] (MRCLAM robot 4 has a 2 s gap).
  double max_reference_gap = 0.5;
  // Added to the odometry (ENCODER / ODOM) timestamps before they are matched with the reference
  // [s]: a positive value says the odometry was logged early. MRCLAM's velocities lead the Vicon
  // motion by about 0.25 s (ML_CALIBRATION.md).
  double odometry_time_offset = 0.0;
};

// Which Freiburg relations become samples.
struct RelationSampleOptions {
  // Skip relations spanning more than this [s]. The Freiburg files mix relations between nearby
  // scans with loop-closing ones hundreds of seconds apart (aces: 85 of 1279 span > 100 s;
  // intel: 1196 of 2984), over which the odometry has drifted by metres.
  double max_duration = std::numeric_limits<double>::infinity();
};

// ENCODER + TRUEPOS (simulated or real): increments are the encoder count changes between
// consecutive ENCODER records, the reference is the ground truth interpolated at the interval's
// end records. `nominal` defaults to the log's PARAM model (InputError if absent). With
// `sensor_mount`, the reference is the displacement of a sensor mounted at that pose on the true
// robot (as a scan matcher would see it) and sensor_reference is set. Throws InputError when the
// log lacks encoders or ground truth, or no sample results.
CalibrationData calibration_data_from_encoders(const Log& log, const SampleIntervalOptions& intervals = {},
                                               std::optional<NominalModel> nominal = std::nullopt,
                                               std::optional<Pose2> sensor_mount = std::nullopt);

// ODOM poses + Freiburg relations: one sample per relation (t1, t2), its increments the ODOM pose
// changes between the records inside [t1, t2] (the end poses interpolated), reduced to arcs
// (kBodyIncrements); samples in order of t1. Uses the FLASER odometry poses for logs without
// ODOM (mit-csail). Relations outside the odometry's time span are skipped. Throws InputError
// without relations, without odometry, or when no relation lies inside the odometry.
CalibrationData calibration_data_from_relations(const Log& log, const RelationSampleOptions& options = {});

// ODOM velocities (tv, rv, each held until the next record — MRCLAM) + ground truth
// (kVelocityIntegrals); intervals cut as for encoders. Throws InputError like the above.
CalibrationData calibration_data_from_velocities(const Log& log, const SampleIntervalOptions& intervals = {});

// Censi et al.'s tuples: one sample per tuple with a single increment of wheel angles
// (T·phi_l, T·phi_r) over T (kWheelAngles), the reference being the scan matcher's sensor
// displacement (sensor_reference = true). The nominal Khepera III values r = 21 mm, b = 90 mm
// (the upstream solver's E_b divides by 0.09 m) only serve as the uncalibrated comparison.
CalibrationData calibration_data_from_wheel_speed_tuples(std::span<const WheelSpeedTuple> tuples,
                                                         double nominal_radius = 0.021, double nominal_axle = 0.09);

// Relative-motion pairs (stachniss_ls_calib): one sample per row, its single increment the
// odometry displacement reduced to an arc (kBodyIncrements), the reference the scan-matched
// displacement taken as the robot's (sensor_reference = false; set it and the nominal sensor
// pose on the result to calibrate a sensor mount as well).
CalibrationData calibration_data_from_motion_pairs(std::span<const RelativeMotionPair> pairs);

// Tick motions (grisetti_diffdrive): one sample per row (kWheelTicks). The file gives no nominal
// model; `nominal` states it (default: the ticks' unit taken as 1 m, the left encoder counting
// backwards as the data show, B = 1 m).
CalibrationData calibration_data_from_tick_motions(std::span<const TickMotion> rows,
                                                   const NominalModel& nominal = {-1.0, 1.0, 1.0});

// The samples of a calibration data set's records, each kind by its function above with its
// defaults; CalibrationData::source names the file(s). InputError when there is none.
CalibrationData calibration_data_from_records(const CalibrationRecords& records);

// Odometry displacement (dx, dy, dθ) in its start frame → the circular arc through it:
// d = chord · (θ/2) / sin(θ/2), signed by the chord's forward component. Exact for arcs.
OdometryIncrement arc_increment(const Pose2& delta, double dt = 0.0);

// The samples [begin, end) of `data` (same kind and nominal values), e.g. to hold some out.
CalibrationData subset(const CalibrationData& data, std::size_t begin, std::size_t end);

}  // namespace locbench::calibration
