#pragma once
// The global-localization options, each field stated once (name, unit, allowed range, meaning;
// the struct headers explain the defaults). The visitors give JSON (options_json.cpp), the
// range checks of each validate() and the docs table (core/option_fields.h).
#include "baselines/global/grid_markov.h"
#include "baselines/global/likelihood_field.h"
#include "baselines/global/monte_carlo_localization.h"
#include "baselines/global/odometry_motion_model.h"
#include "core/input_limits.h"
#include "core/option_fields.h"
#include "core/units.h"

namespace locbench::baselines::global {

template <class V>
void visit_fields(V& v, OdometryMotionOptions& o) {
  v.field("alpha1", o.alpha1, "rad²/rad²", non_negative(), "rotation noise from rotation");
  v.field("alpha2", o.alpha2, "rad²/m²", non_negative(), "rotation noise from translation");
  v.field("alpha3", o.alpha3, "m²/m²", non_negative(), "translation noise from translation");
  v.field("alpha4", o.alpha4, "m²/rad²", non_negative(), "translation noise from rotation");
  v.field("min_translation_sigma", o.min_translation_sigma, "m", non_negative(), "σ floor per update");
  v.field("min_rotation_sigma", o.min_rotation_sigma, "rad", non_negative(), "σ floor per update");
}

template <class V>
void visit_fields(V& v, LikelihoodFieldOptions& o) {
  v.field("resolution", o.resolution, "m", positive(), "distance-grid cell");
  v.field("max_distance", o.max_distance, "m", positive(), "distances are clamped here");
  v.field("sigma_hit", o.sigma_hit, "m", positive(), "σ of a hit");
  v.field("z_hit", o.z_hit, "", non_negative(), "weight of the hit density");
  v.field("z_random", o.z_random, "", non_negative(), "weight of the uniform density");
  v.field("z_max", o.z_max, "m", positive(), "range of the uniform random-return density");
  v.field("margin", o.margin, "m", non_negative(), "grid extent beyond the map's bounding box");
  v.field("beams", o.beams, "", at_least(1), "beams used per scan");
}

template <class V>
void visit_fields(V& v, MclOptions& o) {
  v.nested("motion", o.motion, "OdometryMotionOptions");
  v.nested("field", o.field, "LikelihoodFieldOptions");
  v.field("initial_particles", o.initial_particles, "", closed(1, limits::kMclParticles.max),
          "drawn uniformly for global localization");
  v.field("min_particles", o.min_particles, "", closed(1, limits::kMclParticles.max), "KLD lower bound");
  v.field("max_particles", o.max_particles, "", closed(1, limits::kMclParticles.max),
          "KLD upper bound (≥ min_particles)");
  v.flag("kld", o.kld, "false: keep max_particles");
  v.field("kld_epsilon", o.kld_epsilon, "", positive(), "ε, the K-L bound");
  v.field("kld_z", o.kld_z, "", any_finite(), "z_{1−δ}");
  v.field("kld_bin", o.kld_bin, "m, m, rad", positive(), "histogram bin (x, y, θ), each > 0");
  v.flag("inject", o.inject, "augmented MCL");
  v.field("alpha_slow", o.alpha_slow, "", closed(0.0, 1.0), "slow average rate (< alpha_fast)");
  v.field("alpha_fast", o.alpha_fast, "", open_closed(0.0, 1.0), "fast average rate");
  v.field("update_min_distance", o.update_min_distance, "m", non_negative(), "odometry between updates");
  v.field("update_min_angle", o.update_min_angle, "rad", non_negative(), "odometry between updates");
}

template <class V>
void visit_fields(V& v, GridMarkovOptions& o) {
  v.nested("motion", o.motion, "OdometryMotionOptions");
  v.nested("field", o.field, "LikelihoodFieldOptions");
  v.field("cell_size", o.cell_size, "m", positive(), "grid cell");
  v.field("angular_cell", o.angular_cell, "rad", open_closed(0.0, kPi), "heading cell");
  v.field("update_min_distance", o.update_min_distance, "m", non_negative(), "odometry between updates");
  v.field("update_min_angle", o.update_min_angle, "rad", non_negative(), "odometry between updates");
  v.field("prune_threshold", o.prune_threshold, "", non_negative(), "cells below this × the maximum are not moved");
  v.field("uniform_mix", o.uniform_mix, "", closed_open(0.0, 1.0), "mass spread uniformly after each update");
  v.field("max_cells", o.max_cells, "", closed(1.0, limits::kGridMarkovCells.max), "refuse larger grids (memory)");
}

}  // namespace locbench::baselines::global
