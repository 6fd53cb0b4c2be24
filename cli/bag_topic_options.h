#pragma once
// --odom, --truth, --scan, --heading, --joints: a bag's topics chosen by option, as every verb that reads a
// log declares them (the same choice as LOG#odom=…,truth=…; datasets/io/bag_log.h).
#include <CLI/CLI.hpp>
#include <string>

namespace locbench::cli {

struct BagTopicArgs {
  std::string odom, truth, scan, heading, joints;
};

void add_bag_topic_options(CLI::App* cmd, BagTopicArgs& topics);

// `spec` with the topics given appended after its '#' (they win over the same key written there);
// `spec` itself when none is given. Throws UsageError when topics are given for a log that is not
// a bag.
std::string with_bag_topics(const std::string& spec, const BagTopicArgs& topics);

}  // namespace locbench::cli
