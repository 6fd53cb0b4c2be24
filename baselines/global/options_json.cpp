// JSON to/from of the global-localization options (strict: unknown keys and wrong types throw
// UsageError naming the key; values in SI units, angles in radians).
#include "core/json_options.h"
#include "baselines/global/grid_markov.h"
#include "baselines/global/likelihood_field.h"
#include "baselines/global/monte_carlo_localization.h"
#include "baselines/global/odometry_motion_model.h"

namespace locbench::global {

void to_json(nlohmann::json& j, const OdometryMotionOptions& o) {
  j = {{"alpha1", o.alpha1}, {"alpha2", o.alpha2}, {"alpha3", o.alpha3}, {"alpha4", o.alpha4},
       {"min_translation_sigma", o.min_translation_sigma},
       {"min_rotation_sigma", o.min_rotation_sigma}};
}
void from_json(const nlohmann::json& j, OdometryMotionOptions& o) {
  StrictJsonReader r(j, "OdometryMotionOptions");
  r.read("alpha1", o.alpha1);
  r.read("alpha2", o.alpha2);
  r.read("alpha3", o.alpha3);
  r.read("alpha4", o.alpha4);
  r.read("min_translation_sigma", o.min_translation_sigma);
  r.read("min_rotation_sigma", o.min_rotation_sigma);
  r.finish();
  validate(o);
}

void to_json(nlohmann::json& j, const LikelihoodFieldOptions& o) {
  j = {{"resolution", o.resolution}, {"max_distance", o.max_distance}, {"sigma_hit", o.sigma_hit},
       {"z_hit", o.z_hit},           {"z_random", o.z_random},         {"z_max", o.z_max},
       {"margin", o.margin},         {"beams", o.beams}};
}
void from_json(const nlohmann::json& j, LikelihoodFieldOptions& o) {
  StrictJsonReader r(j, "LikelihoodFieldOptions");
  r.read("resolution", o.resolution);
  r.read("max_distance", o.max_distance);
  r.read("sigma_hit", o.sigma_hit);
  r.read("z_hit", o.z_hit);
  r.read("z_random", o.z_random);
  r.read("z_max", o.z_max);
  r.read("margin", o.margin);
  r.read("beams", o.beams);
  r.finish();
  validate(o);
}

void to_json(nlohmann::json& j, const MclOptions& o) {
  j = {{"motion", o.motion},
       {"field", o.field},
       {"initial_particles", o.initial_particles},
       {"min_particles", o.min_particles},
       {"max_particles", o.max_particles},
       {"kld", o.kld},
       {"kld_epsilon", o.kld_epsilon},
       {"kld_z", o.kld_z},
       {"kld_bin", vector3_json(o.kld_bin)},
       {"inject", o.inject},
       {"alpha_slow", o.alpha_slow},
       {"alpha_fast", o.alpha_fast},
       {"update_min_distance", o.update_min_distance},
       {"update_min_angle", o.update_min_angle}};
}
void from_json(const nlohmann::json& j, MclOptions& o) {
  StrictJsonReader r(j, "MclOptions");
  r.read_object("motion", o.motion);
  r.read_object("field", o.field);
  r.read("initial_particles", o.initial_particles);
  r.read("min_particles", o.min_particles);
  r.read("max_particles", o.max_particles);
  r.read("kld", o.kld);
  r.read("kld_epsilon", o.kld_epsilon);
  r.read("kld_z", o.kld_z);
  r.read("kld_bin", o.kld_bin);
  r.read("inject", o.inject);
  r.read("alpha_slow", o.alpha_slow);
  r.read("alpha_fast", o.alpha_fast);
  r.read("update_min_distance", o.update_min_distance);
  r.read("update_min_angle", o.update_min_angle);
  r.finish();
  validate(o);
}

void to_json(nlohmann::json& j, const GridMarkovOptions& o) {
  j = {{"motion", o.motion},
       {"field", o.field},
       {"cell_size", o.cell_size},
       {"angular_cell", o.angular_cell},
       {"update_min_distance", o.update_min_distance},
       {"update_min_angle", o.update_min_angle},
       {"prune_threshold", o.prune_threshold},
       {"uniform_mix", o.uniform_mix},
       {"max_cells", o.max_cells}};
}
void from_json(const nlohmann::json& j, GridMarkovOptions& o) {
  StrictJsonReader r(j, "GridMarkovOptions");
  r.read_object("motion", o.motion);
  r.read_object("field", o.field);
  r.read("cell_size", o.cell_size);
  r.read("angular_cell", o.angular_cell);
  r.read("update_min_distance", o.update_min_distance);
  r.read("update_min_angle", o.update_min_angle);
  r.read("prune_threshold", o.prune_threshold);
  r.read("uniform_mix", o.uniform_mix);
  r.read("max_cells", o.max_cells);
  r.finish();
  validate(o);
}

}  // namespace locbench::global
