#include "core/json_options.h"

#include <algorithm>
#include <cstdint>

namespace locbench {
namespace {

[[noreturn]] void throw_at(const std::string& source, const std::string& message) {
  if (source.empty()) throw UsageError(message);
  throw InputError(source, 0, message);
}

}  // namespace

std::string json_type_name(const nlohmann::json& v) {
  if (v.is_boolean()) return "boolean";
  if (v.is_number()) return "number";
  return v.type_name();
}

StrictJsonReader::StrictJsonReader(const nlohmann::json& j, std::string path, std::string source)
    : j_(j), path_(std::move(path)), source_(std::move(source)) {
  if (!j_.is_object()) {
    throw_at(source_,
             (path_.empty() ? std::string("top level") : path_) + ": expected an object, found " + json_type_name(j_));
  }
}

void StrictJsonReader::fail(const std::string& key, const std::string& why) const {
  const std::string where = path_of(key);
  throw_at(source_, where.empty() ? why : where + ": " + why);
}

const nlohmann::json* StrictJsonReader::raw(const char* key) {
  if (std::find(known_.begin(), known_.end(), key) == known_.end()) known_.emplace_back(key);
  const auto it = j_.find(key);
  return it == j_.end() ? nullptr : &*it;
}

const nlohmann::json& StrictJsonReader::required(const char* key) {
  const nlohmann::json* v = raw(key);
  if (!v) fail(key, "missing field");
  return *v;
}

void StrictJsonReader::read(const char* key, double& out) {
  const auto* v = raw(key);
  if (!v) return;
  if (!v->is_number()) fail(key, "expected a number, found " + json_type_name(*v));
  out = v->get<double>();
}

void StrictJsonReader::read(const char* key, int& out) {
  const auto* v = raw(key);
  if (!v) return;
  if (!v->is_number_integer()) fail(key, "expected an integer, found " + json_type_name(*v));
  const auto i = v->get<std::int64_t>();
  if (i < -2147483647 || i > 2147483647) fail(key, "integer out of range");
  out = static_cast<int>(i);
}

void StrictJsonReader::read(const char* key, std::size_t& out) {
  const auto* v = raw(key);
  if (!v) return;
  if (!v->is_number_integer() || v->get<std::int64_t>() < 0) {
    fail(key, "expected a whole number ≥ 0, found " + (v->is_number() ? v->dump() : json_type_name(*v)));
  }
  out = v->get<std::size_t>();
}

void StrictJsonReader::read(const char* key, bool& out) {
  const auto* v = raw(key);
  if (!v) return;
  if (!v->is_boolean()) fail(key, "expected true or false, found " + json_type_name(*v));
  out = v->get<bool>();
}

void StrictJsonReader::read(const char* key, std::string& out) {
  const auto* v = raw(key);
  if (!v) return;
  if (!v->is_string()) fail(key, "expected a string, found " + json_type_name(*v));
  out = v->get<std::string>();
}

void read_numbers(const nlohmann::json& v, double* out, std::size_t n, const std::string& path,
                  const std::string& source) {
  if (!v.is_array() || v.size() != n) {
    throw_at(source, path + ": expected an array of " + std::to_string(n) + " numbers, found " +
                         (v.is_array() ? "an array of " + std::to_string(v.size()) : json_type_name(v)));
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!v[i].is_number()) {
      throw_at(source, path + "[" + std::to_string(i) + "]: expected a number, found " + json_type_name(v[i]));
    }
    out[i] = v[i].get<double>();
  }
}

void StrictJsonReader::read(const char* key, Pose2& out) {
  if (const auto* v = raw(key)) {
    double p[3];
    read_numbers(*v, p, 3, path_of(key), source_);
    out = Pose2(p[0], p[1], p[2]);
  }
}

StrictJsonReader StrictJsonReader::object(const char* key) {
  const auto* v = raw(key);
  static const nlohmann::json kEmpty = nlohmann::json::object();
  return StrictJsonReader(v ? *v : kEmpty, path_of(key), source_);
}

void StrictJsonReader::allow_only(std::initializer_list<const char*> keys) {
  for (const char* k : keys) raw(k);
  finish();
}

void StrictJsonReader::finish() const {
  for (const auto& item : j_.items()) {
    if (std::find(known_.begin(), known_.end(), item.key()) == known_.end()) {
      std::string list;
      for (const auto& k : known_) list += (list.empty() ? "" : ", ") + k;
      fail(item.key(), "unknown key (expected one of: " + list + ")");
    }
  }
}

}  // namespace locbench
