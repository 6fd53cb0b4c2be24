#pragma once
// Markov localization on a topological map (slides, "实例研究 1 – 拓扑地图", the Dervish robot):
//   action update      p_t(l | o_t) = Σ_l' p(l | l', o_t) p_{t−1}(l')
//   perception update  p_t(l) = p(i | l) p_t(l | o_t)   (optionally divided by p(i))
// The sensor model is a table p(detection | feature) (the slides' Dervish table, rows =
// detections, columns = features); a node has a left and a right side, each a distribution over
// features (a door is closed with 0.6 and open with 0.4 on the slides), and
//   p(i | l) = Π_side Σ_f p(detected_side | f) p(f at side of l).
#include <array>
#include <string>
#include <vector>

namespace locbench::baselines::global {

enum class Feature { kWall, kClosedDoor, kOpenDoor, kOpenHallway, kFoyer };
inline constexpr int kFeatureCount = 5;
enum class Detection { kNothing, kClosedDoor, kOpenDoor, kOpenHallway };
inline constexpr int kDetectionCount = 4;

// p(detection | feature), [detection][feature].
using SensorTable = std::array<std::array<double, kFeatureCount>, kDetectionCount>;
// The Dervish sonar table of the slides (after Siegwart & Nourbakhsh, Table 5.x):
//                         wall  closed door  open door  open hallway  foyer
//   nothing detected      0.70     0.40        0.05        0.001      0.30
//   closed door detected  0.30     0.60        0           0          0.05
//   open door detected    0        0           0.90        0.10       0.15
//   open hallway detected 0        0           0.001       0.90       0.50
SensorTable dervish_sensor_table();

struct FeatureProbability {
  Feature feature = Feature::kWall;
  double probability = 1.0;
};
// What a side of a node really is: one feature (probability 1) or a mixture (a door of unknown
// state: {closed 0.6, open 0.4}).
using SideModel = std::vector<FeatureProbability>;

struct TopologicalNode {
  std::string name;  // "1-2", "2", …
  SideModel left;
  SideModel right;
};

struct TopologicalObservation {
  Detection left = Detection::kNothing;
  Detection right = Detection::kNothing;
};

struct TopologicalMarkovOptions {
  // Divide by p(i) after each perception update. The slides' worked example does not
  // ("为简单起见，此例中不做归一化处理"), which is why its beliefs do not sum to 1.
  bool normalise = false;
};

class TopologicalMarkov {
 public:
  // Throws UsageError for an empty map, a table entry outside [0, 1], a side probability
  // outside [0, 1] or sides whose probabilities do not sum to 1 (±1e-9).
  TopologicalMarkov(std::vector<TopologicalNode> nodes, const SensorTable& table,
                    const TopologicalMarkovOptions& options = {});

  // Sets p(l) for every node; throws UsageError for a wrong size or a negative/non-finite value.
  void set_belief(std::vector<double> belief);
  // transition[l][l'] = p(l | l', o_t), nodes × nodes; UsageError for a wrong shape or a value
  // outside [0, 1]. Columns need not sum to 1 (the slides' example moves 2-3 to 3, 3-4 and 4
  // each with probability 1).
  void action_update(const std::vector<std::vector<double>>& transition);
  // p(i | l) of node l.
  double likelihood(std::size_t node, const TopologicalObservation& i) const;
  void perception_update(const TopologicalObservation& i);

  const std::vector<double>& belief() const { return belief_; }
  const std::vector<TopologicalNode>& nodes() const { return nodes_; }
  // Index of the node named `name`; UsageError if none.
  std::size_t index(const std::string& name) const;

 private:
  double side_likelihood(const SideModel& side, Detection d) const;
  std::vector<TopologicalNode> nodes_;
  SensorTable table_;
  TopologicalMarkovOptions options_;
  std::vector<double> belief_;
};

}  // namespace locbench::baselines::global
