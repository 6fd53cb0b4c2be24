#include "datasets/sim/json_fields.h"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "core/errors.h"
#include "reports/json_file.h"

namespace locbench::sim {

std::string json_type_name(const nlohmann::json& v) {
  if (v.is_boolean()) return "boolean";
  if (v.is_number()) return "number";
  return v.type_name();
}

JsonObject::JsonObject(const nlohmann::json& j, std::string path, std::string source)
    : j_(j), path_(std::move(path)), source_(std::move(source)) {
  if (!j_.is_object()) {
    throw InputError(source_, 0,
                     (path_.empty() ? std::string("top level") : path_) +
                         ": expected an object, found " + json_type_name(j_));
  }
}

void JsonObject::fail(const std::string& key, const std::string& what) const {
  throw InputError(source_, 0, path_of(key) + ": " + what);
}

const nlohmann::json* JsonObject::raw(const char* key) {
  known_.insert(key);
  const auto it = j_.find(key);
  return it == j_.end() ? nullptr : &*it;
}

void JsonObject::read(const char* key, double& out) {
  const auto* v = raw(key);
  if (!v) return;
  if (!v->is_number()) fail(key, "expected a number, found " + json_type_name(*v));
  out = v->get<double>();
}

void JsonObject::read(const char* key, int& out) {
  const auto* v = raw(key);
  if (!v) return;
  if (!v->is_number_integer()) fail(key, "expected an integer, found " + json_type_name(*v));
  const auto i = v->get<std::int64_t>();
  if (i < -2147483647 || i > 2147483647) fail(key, "integer out of range");
  out = static_cast<int>(i);
}

void JsonObject::read(const char* key, bool& out) {
  const auto* v = raw(key);
  if (!v) return;
  if (!v->is_boolean()) fail(key, "expected true or false, found " + json_type_name(*v));
  out = v->get<bool>();
}

void JsonObject::read(const char* key, std::string& out) {
  const auto* v = raw(key);
  if (!v) return;
  if (!v->is_string()) fail(key, "expected a string, found " + json_type_name(*v));
  out = v->get<std::string>();
}

void read_numbers(const nlohmann::json& v, double* out, std::size_t n, const std::string& path,
                  const std::string& source) {
  if (!v.is_array() || v.size() != n) {
    throw InputError(
        source, 0,
        path + ": expected an array of " + std::to_string(n) + " numbers, found " +
            (v.is_array() ? "an array of " + std::to_string(v.size()) : json_type_name(v)));
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!v[i].is_number()) {
      throw InputError(
          source, 0,
          path + "[" + std::to_string(i) + "]: expected a number, found " + json_type_name(v[i]));
    }
    out[i] = v[i].get<double>();
  }
}

void JsonObject::read(const char* key, Eigen::Vector2d& out) {
  if (const auto* v = raw(key)) read_numbers(*v, out.data(), 2, path_of(key), source_);
}

void JsonObject::read(const char* key, Eigen::Vector4d& out) {
  if (const auto* v = raw(key)) read_numbers(*v, out.data(), 4, path_of(key), source_);
}

void JsonObject::read(const char* key, Pose2& out) {
  if (const auto* v = raw(key)) {
    double p[3];
    read_numbers(*v, p, 3, path_of(key), source_);
    out = Pose2(p[0], p[1], p[2]);
  }
}

JsonObject JsonObject::object(const char* key) {
  const auto* v = raw(key);
  static const nlohmann::json kEmpty = nlohmann::json::object();
  return JsonObject(v ? *v : kEmpty, path_of(key), source_);
}

void JsonObject::finish() const {
  for (const auto& item : j_.items()) {
    if (!known_.contains(item.key())) {
      throw InputError(source_, 0, "unknown key '" + path_of(item.key()) + "'");
    }
  }
}

nlohmann::json parse_json_text(const std::string& text, const std::string& source) {
  return reports::parse_json_text(text, source);
}

nlohmann::json read_json_file(const std::string& path) { return reports::read_json_file(path, "JSON file"); }

}  // namespace locbench::sim
