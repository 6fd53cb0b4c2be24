#include "baselines/global/topological_markov.h"

#include <cmath>

#include "core/errors.h"

namespace locbench::baselines::global {

SensorTable dervish_sensor_table() {
  return {{{0.70, 0.40, 0.05, 0.001, 0.30},
           {0.30, 0.60, 0.0, 0.0, 0.05},
           {0.0, 0.0, 0.90, 0.10, 0.15},
           {0.0, 0.0, 0.001, 0.90, 0.50}}};
}

namespace {
void check_side(const SideModel& side, const std::string& node, const char* which) {
  double sum = 0.0;
  for (const FeatureProbability& f : side) {
    if (!(f.probability >= 0.0 && f.probability <= 1.0)) {
      throw UsageError("topological map: node " + node + " " + which + ": probability outside [0, 1]");
    }
    sum += f.probability;
  }
  if (std::abs(sum - 1.0) > 1e-9) {
    throw UsageError("topological map: node " + node + " " + which + ": feature probabilities must sum to 1");
  }
}
}  // namespace

TopologicalMarkov::TopologicalMarkov(std::vector<TopologicalNode> nodes, const SensorTable& table,
                                     const TopologicalMarkovOptions& options)
    : nodes_(std::move(nodes)), table_(table), options_(options), belief_(nodes_.size(), 0.0) {
  if (nodes_.empty()) throw UsageError("topological map: no nodes");
  for (const auto& row : table_) {
    for (double p : row) {
      if (!(p >= 0.0 && p <= 1.0)) throw UsageError("sensor table: entry outside [0, 1]");
    }
  }
  for (const TopologicalNode& n : nodes_) {
    check_side(n.left, n.name, "left");
    check_side(n.right, n.name, "right");
  }
}

void TopologicalMarkov::set_belief(std::vector<double> belief) {
  if (belief.size() != nodes_.size()) {
    throw UsageError("topological Markov: belief has " + std::to_string(belief.size()) + " entries for " +
                     std::to_string(nodes_.size()) + " nodes");
  }
  for (double p : belief) {
    if (!(std::isfinite(p) && p >= 0.0)) throw UsageError("topological Markov: negative belief");
  }
  belief_ = std::move(belief);
}

void TopologicalMarkov::action_update(const std::vector<std::vector<double>>& transition) {
  const std::size_t n = nodes_.size();
  if (transition.size() != n) throw UsageError("topological Markov: transition needs one row per node");
  std::vector<double> next(n, 0.0);
  for (std::size_t l = 0; l < n; ++l) {
    if (transition[l].size() != n) {
      throw UsageError("topological Markov: transition row " + std::to_string(l) + " needs one column per node");
    }
    for (std::size_t lp = 0; lp < n; ++lp) {
      const double p = transition[l][lp];
      if (!(p >= 0.0 && p <= 1.0)) throw UsageError("topological Markov: transition outside [0, 1]");
      next[l] += p * belief_[lp];
    }
  }
  belief_ = std::move(next);
}

double TopologicalMarkov::side_likelihood(const SideModel& side, Detection d) const {
  double p = 0.0;
  for (const FeatureProbability& f : side) {
    p += table_[static_cast<std::size_t>(d)][static_cast<std::size_t>(f.feature)] * f.probability;
  }
  return p;
}

double TopologicalMarkov::likelihood(std::size_t node, const TopologicalObservation& i) const {
  if (node >= nodes_.size()) throw UsageError("topological Markov: no node " + std::to_string(node));
  const TopologicalNode& n = nodes_[node];
  return side_likelihood(n.left, i.left) * side_likelihood(n.right, i.right);
}

void TopologicalMarkov::perception_update(const TopologicalObservation& i) {
  double sum = 0.0;
  for (std::size_t l = 0; l < nodes_.size(); ++l) {
    belief_[l] *= likelihood(l, i);
    sum += belief_[l];
  }
  if (options_.normalise) {
    if (sum <= 0.0) throw UsageError("topological Markov: the observation is impossible everywhere");
    for (double& p : belief_) p /= sum;
  }
}

std::size_t TopologicalMarkov::index(const std::string& name) const {
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    if (nodes_[i].name == name) return i;
  }
  throw UsageError("topological map: no node named " + name);
}

}  // namespace locbench::baselines::global
