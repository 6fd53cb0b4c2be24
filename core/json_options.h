#pragma once
// Strict JSON reading of option structs for to_json/from_json pairs: absent keys keep their
// defaults, unknown keys, wrong types and wrong array sizes throw UsageError naming the key.
// Values are in SI units (m, rad) like the structs themselves.
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "core/errors.h"

namespace locbench {

class StrictJsonReader {
 public:
  // `what` names the options struct in messages ("SageHusaOptions").
  StrictJsonReader(const nlohmann::json& j, std::string what) : j_(j), what_(std::move(what)) {
    if (!j_.is_object()) fail("", "expected a JSON object");
  }

  void read(const char* key, double& out) {
    if (const nlohmann::json* v = find(key)) {
      if (!v->is_number()) fail(key, "expected a number");
      out = v->get<double>();
    }
  }
  void read(const char* key, int& out) {
    if (const nlohmann::json* v = find(key)) {
      if (!v->is_number_integer()) fail(key, "expected an integer");
      out = v->get<int>();
    }
  }
  void read(const char* key, bool& out) {
    if (const nlohmann::json* v = find(key)) {
      if (!v->is_boolean()) fail(key, "expected true or false");
      out = v->get<bool>();
    }
  }
  void read(const char* key, std::string& out) {
    if (const nlohmann::json* v = find(key)) {
      if (!v->is_string()) fail(key, "expected a string");
      out = v->get<std::string>();
    }
  }
  void read(const char* key, Eigen::Vector3d& out) {
    if (const nlohmann::json* v = find(key)) {
      if (!v->is_array() || v->size() != 3) fail(key, "expected an array of 3 numbers");
      for (std::size_t i = 0; i < 3; ++i) {
        if (!(*v)[i].is_number()) fail(key, "expected an array of 3 numbers");
        out(static_cast<Eigen::Index>(i)) = (*v)[i].get<double>();
      }
    }
  }
  // A nested options struct with its own from_json.
  template <class T>
  void read_object(const char* key, T& out) {
    if (const nlohmann::json* v = find(key)) {
      try {
        from_json(*v, out);
      } catch (const UsageError& e) {
        fail(key, e.what());
      }
    }
  }
  // Throws for the first key that was never asked for.
  void finish() const {
    for (auto it = j_.begin(); it != j_.end(); ++it) {
      if (!known_.contains(it.key())) fail(it.key(), "unknown key");
    }
  }

  [[noreturn]] void fail(const std::string& key, const std::string& why) const {
    throw UsageError(what_ + (key.empty() ? "" : "." + key) + ": " + why);
  }

 private:
  const nlohmann::json* find(const char* key) {
    known_.insert(key);
    const auto it = j_.find(key);
    return it == j_.end() ? nullptr : &*it;
  }

  const nlohmann::json& j_;
  std::string what_;
  std::set<std::string> known_;
};

inline nlohmann::json vector3_json(const Eigen::Vector3d& v) {
  return nlohmann::json::array({v(0), v(1), v(2)});
}

}  // namespace locbench
