#pragma once
// --odom, --truth, --scan, --heading, --joints: a bag's topics chosen by option, as every verb that reads a
// log declares them (the same choice as LOG#odom=…,truth=…; datasets/io/bag_log.h).
#include <CLI/CLI.hpp>
#include <functional>
#include <memory>
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

// Adds the topic options to `cmd` and returns the verb's action: the topics given appended to the
// log spec args->*log (with_bag_topics), then run(*args).
template <class Args, class Run>
std::function<int()> bag_topic_action(CLI::App* cmd, std::shared_ptr<Args> args, std::string Args::*log, Run run) {
  add_bag_topic_options(cmd, args->topics);
  return [args, log, run] {
    (*args).*log = with_bag_topics((*args).*log, args->topics);
    return run(*args);
  };
}

}  // namespace locbench::cli
