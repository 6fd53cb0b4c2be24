// Experiment global/topological_example: the slides' worked example of Markov localization on a
// topological map (Dervish, "马尔可夫定位：实例研究 1 – 拓扑地图"), run through
// baselines/global/topological_markov with the slides' sensor table, prior and action model,
// beside the published figures (p(i|2) = 0.324, p(i|4) = 0.09, posteriors 0.324 and 0.018,
// 18 : 1).
#include <fmt/format.h>

#include "baselines/global/topological_markov.h"
#include "core/checksum.h"
#include "experiment_framework/options_experiment.h"
#include "experiment_framework/registry.h"

namespace locbench::experiments::global_topological_example {

const ExperimentInfo kInfo{.name = "global/topological_example",
                           .description =
                               "Markov localization on the slides' topological map (Dervish sensor table): prior "
                               "1.0 / 0.2, action 1-2 → 2 and 2-3 → 3, 3-4, 4, observation 'open hallway left, open "
                               "door right' → 0.324 at node 2 and 0.018 at node 4 (18 : 1)"};

using namespace locbench::baselines::global;

struct Options {
  double prior_1_2 = 1.0;
  double prior_2_3 = 0.2;
  double door_open_probability = 0.4;
  bool normalise = false;
};
template <class V>
void visit_fields(V& v, Options& o) {
  v.field("prior_1_2", o.prior_1_2, "", non_negative(), "prior belief at node 1-2");
  v.field("prior_2_3", o.prior_2_3, "", non_negative(), "prior belief at node 2-3");
  v.field("door_open_probability", o.door_open_probability, "", closed(0.0, 1.0),
          "probability that node 2's door is open");
  v.flag("normalise", o.normalise, "normalise the belief after each update");
}

class GlobalTopological final : public OptionsExperiment<Options> {
 public:
  reports::ExperimentResults run_with(const Options& o, const RunOptions&) const override {
    const double p12 = o.prior_1_2;
    const double p23 = o.prior_2_3;
    const double open = o.door_open_probability;
    const SideModel wall = {{Feature::kWall, 1.0}}, hall = {{Feature::kOpenHallway, 1.0}};
    const SideModel door = {{Feature::kClosedDoor, 1.0 - open}, {Feature::kOpenDoor, open}};
    TopologicalMarkov m({{"1-2", wall, wall},
                         {"2", hall, door},
                         {"2-3", wall, wall},
                         {"3", wall, wall},
                         {"3-4", wall, wall},
                         {"4", hall, hall}},
                        dervish_sensor_table(), {o.normalise});
    m.set_belief({p12, 0.0, p23, 0.0, 0.0, 0.0});
    std::vector<std::vector<double>> t(6, std::vector<double>(6, 0.0));
    t[1][0] = t[3][2] = t[4][2] = t[5][2] = 1.0;
    m.action_update(t);
    const TopologicalObservation obs{Detection::kOpenHallway, Detection::kOpenDoor};
    const double l2 = m.likelihood(1, obs), l3 = m.likelihood(3, obs), l34 = m.likelihood(4, obs),
                 l4 = m.likelihood(5, obs);
    m.perception_update(obs);
    const double b2 = m.belief()[1], b4 = m.belief()[5];

    const nlohmann::json config = options_json(o);
    reports::ExperimentResults out = start_results(config);
    out.datasets.push_back(
        {"slides/dervish_topological", "slides (transcribed)", text_checksum(config.dump()), 6, 0.0});
    const auto add = [&](const char* variant, double v) {
      out.results.push_back(reports::make_estimate("topological_markov", "dervish", variant, "", v, 0.0, 1));
    };
    add("likelihood_node_2", l2);
    add("likelihood_node_4", l4);
    add("posterior_node_2", b2);
    add("posterior_node_4", b4);
    add("posterior_ratio_2_to_4", b2 / b4);
    reports::PublishedComparison p;
    p.source = "slides, Markov localization case study 1 (topological map, Dervish)";
    p.quantity = "sensor likelihoods p(i|l) and unnormalised posteriors";
    p.unit = "";
    p.rows = {{"p(i|2)", 0.324, l2},
              {"p(i|3)", 0.0, l3},
              {"p(i|3-4)", 0.0, l34},
              {"p(i|4)", 0.09, l4},
              {"p_t(2)", 0.324, b2},
              {"p_t(4)", 0.018, b4},
              {"p_t(2) : p_t(4)", 18.0, b2 / b4}};
    p.note =
        "The slides label the first posterior line p_t(1|o_t, i); the node it computes is 2 "
        "(the only one 1-2 can reach). Not normalised, as on the slides.";
    p.claim = "after 'open hallway left, open door right' the robot is at node 2 with odds 18 : 1 over node 4";
    p.tolerance = 5e-4;
    p.tolerance_basis = "half a unit in the slides' last printed digit (0.001)";
    out.published.push_back(std::move(p));
    out.notes.push_back(
        fmt::format("p(i|2) = {:.3f}, p(i|4) = {:.3f}; posteriors {:.3f} at node 2 and "
                    "{:.3f} at node 4, {:.1f} : 1 (slides: 0.324, 0.018, 18 : 1).",
                    l2, l4, b2, b4, b2 / b4));
    return out;
  }
};

const Registration<GlobalTopological> global_topological_example_registration(kInfo);

}  // namespace locbench::experiments::global_topological_example
