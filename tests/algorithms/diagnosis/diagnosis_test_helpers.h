#pragma once
// Reading a diagnosis in tests: find a cause, ask whether it was kept, print the whole verdict
// when an expectation fails; what the histogram reader says of malformed input; the points of the
// derivative tests.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "algorithms/diagnosis/diagnosis.h"
#include "tests/input_error_message.h"

namespace locbench::diagnosis::test_support {

// A model with the fields whose exact derivatives are checked, and the central-difference step of
// each (the derivative tests of the odometry and landmark likelihoods).
template <class Model>
struct DerivativePoint {
  Model model;
  std::vector<double Model::*> fields;
  std::vector<double> steps;
  std::string what;
};

inline const Cause* find_cause(const Diagnosis& d, const std::string& id) {
  for (const auto& c : d.causes) {
    if (c.id == id) return &c;
  }
  return nullptr;
}

inline bool detected(const Diagnosis& d, const std::string& id) {
  return std::find(d.detected.begin(), d.detected.end(), id) != d.detected.end();
}

// One line per cause: its id, [D] when kept, its likelihood ratio, threshold and parameters.
inline std::string causes_summary(const std::vector<Cause>& causes) {
  std::string s;
  for (const auto& c : causes) {
    s += "\n  " + c.id + (c.detected ? " [D]" : "") + " LR=" + std::to_string(c.value) +
         " thr=" + std::to_string(c.threshold);
    for (const auto& p : c.parameters)
      s += " " + p.name + "=" + std::to_string(p.value) + "[" + std::to_string(p.lo) + "," + std::to_string(p.hi) + "]";
  }
  return s;
}

inline std::string summary(const Diagnosis& d) {
  std::string s = "detected:";
  for (const auto& id : d.detected) s += " " + id;
  s += causes_summary(d.causes);
  for (const auto& u : d.unexplained)
    s += "\n  unexplained " + u.test + " " + u.residual + " " + u.variable + " (" + u.reason + ")";
  return s + "\n  verdict: " + d.verdict;
}

// What read_histogram says of the JSON `text` read as h.json (its InputError; empty when it reads).
inline std::string histogram_error(const char* text) {
  return testing::input_error_message([&] { read_histogram(nlohmann::json::parse(text), "h.json"); });
}

// Expects each histogram text's error to say the words given with it.
inline void expect_histogram_errors(const std::vector<std::pair<const char*, const char*>>& cases) {
  for (const auto& [text, says] : cases) {
    EXPECT_NE(histogram_error(text).find(says), std::string::npos) << text << " → " << histogram_error(text);
  }
}

}  // namespace locbench::diagnosis::test_support
