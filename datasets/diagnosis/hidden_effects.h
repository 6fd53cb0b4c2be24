#pragma once
// Simulated logs with hidden effects from the diagnosis catalog, for testing `diagnose`: a robot
// drives a random waypoint path in an empty world logging ENCODER (or ODOM), COMPASS and noisy
// TRUEPOS records; each effect changes the true robot or a sensor while the log's PARAM records
// keep declaring the nominal model. The truth of each effect is returned beside the log for the
// tests to compare with the report; the diagnosis never sees it.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/log.h"

namespace locbench::sim {

struct HiddenEffect {
  std::string id;    // a catalog id (algorithms/diagnosis/diagnosis.h)
  double magnitude;  // see hidden_effect_ids(): the deviation from the nominal model
};

// What the log carries as the reference the diagnosis takes residuals against.
enum class GeneratedReference {
  kTruePose,   // TRUEPOS (noisy, see reference_noise_*)
  kRelations,  // Freiburg-style relations between odometry instants 1 s apart, no TRUEPOS
  kCompass,    // no TRUEPOS: the compass is the only reference (headings, no distance)
};

struct GeneratorOptions {
  GeneratedReference reference = GeneratedReference::kTruePose;
  int waypoints = 16;                   // random waypoints in a square of side `area`
  double area = 8.0;                    // [m]
  double reference_noise_xy = 1e-3;     // TRUEPOS white noise [m] (a motion-capture system)
  double reference_noise_theta = 1e-3;  // [rad]
  bool velocity_odometry = false;       // log ODOM (dead-reckoned pose) instead of ENCODER
  bool compass = true;                  // log a 10 Hz compass (continuous, σ = 0.2°, declared so)
};

struct GeneratedLog {
  Log log;
  std::vector<HiddenEffect> effects;
  // The true value of each effect's parameters, "id.parameter" → value (catalog names).
  std::map<std::string, double> truth;
};

// Every id the generator can hide, with the unit of its magnitude.
std::vector<std::pair<std::string, std::string>> hidden_effect_ids();
// Throws UsageError for an unknown id or an invalid magnitude.
GeneratedLog generate_log(const std::vector<HiddenEffect>& effects, std::uint64_t seed,
                          const GeneratorOptions& options = {});

}  // namespace locbench::sim
