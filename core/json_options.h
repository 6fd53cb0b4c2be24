#pragma once
// The one strict reader of JSON objects into option structs and input files: absent keys keep
// their defaults (or, through required(), are an error), unknown keys, wrong types and wrong
// array sizes throw naming the key's full path and what was expected. Values are in SI units
// (m, rad) like the structs themselves.
//
// Errors: with a `source` (the file), InputError(source, 0, "path.key: …"), exit 2 naming the
// file; without one (options passed in code or merged from a CLI file that the CLI names),
// UsageError("path.key: …").
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/errors.h"
#include "core/pose2.h"

namespace locbench {

// Reads an array of numbers of fixed size n into out[0..n); names `path` in errors, which are
// InputError(source, …) or, with no source, UsageError.
void read_numbers(const nlohmann::json& v, double* out, std::size_t n, const std::string& path,
                  const std::string& source);

class StrictJsonReader {
 public:
  // `path` is the dotted path of this object in messages: the options struct's name
  // ("SageHusaOptions") or the key path from the top of a file ("compass"; "" for the top).
  // `source` names the file ("" when not read from a file).
  StrictJsonReader(const nlohmann::json& j, std::string path, std::string source = "");

  bool has(const char* key) const { return j_.contains(key); }
  void read(const char* key, double& out);
  void read(const char* key, int& out);
  void read(const char* key, std::size_t& out);
  void read(const char* key, bool& out);
  void read(const char* key, std::string& out);
  // A fixed-size vector (Vector2d, Vector3d, …): an array of exactly N numbers.
  template <int N>
  void read(const char* key, Eigen::Matrix<double, N, 1>& out) {
    if (const nlohmann::json* v = raw(key)) read_numbers(*v, out.data(), N, path_of(key), source_);
  }
  void read(const char* key, Pose2& out);  // [x, y, theta]
  // A nested options struct with its own from_json (errors get this key's path in front).
  template <class T>
  void read_object(const char* key, T& out) {
    if (const nlohmann::json* v = raw(key)) {
      try {
        from_json(*v, out);
      } catch (const UsageError& e) {
        fail(key, e.what());
      }
    }
  }
  // A nested object read by its own reader (which must be an object; absent = empty).
  StrictJsonReader object(const char* key);
  // The raw value of a present key (marks it known), or nullptr when absent.
  const nlohmann::json* raw(const char* key);
  // The raw value of a key that must be present ("missing field" otherwise).
  const nlohmann::json& required(const char* key);
  // Throws for the first key that was never asked for, listing the known ones.
  void finish() const;
  // Declares the object's keys up front and rejects any other at once (for inputs that check
  // their keys before their values).
  void allow_only(std::initializer_list<const char*> keys);

  std::string path_of(const std::string& key) const {
    return path_.empty() ? key : key.empty() ? path_ : path_ + "." + key;
  }
  [[noreturn]] void fail(const std::string& key, const std::string& why) const;
  const std::string& source() const { return source_; }

 private:
  const nlohmann::json& j_;
  std::string path_;
  std::string source_;
  std::vector<std::string> known_;  // in the order asked, for the "expected one of" list
};

// Name of a JSON value's type for messages: "number", "string", "array"...
std::string json_type_name(const nlohmann::json& v);

template <int N>
nlohmann::json vector_json(const Eigen::Matrix<double, N, 1>& v) {
  nlohmann::json a = nlohmann::json::array();
  for (int i = 0; i < N; ++i) a.push_back(v(i));
  return a;
}
inline nlohmann::json vector3_json(const Eigen::Vector3d& v) { return vector_json(v); }

}  // namespace locbench
