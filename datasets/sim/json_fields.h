#pragma once
// Strict reading of JSON objects into option structs: absent keys keep their defaults, unknown
// keys and wrong types throw InputError naming the key's full path ("compass.resolution").
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "core/pose2.h"

namespace locbench::sim {

class JsonObject {
 public:
  // `path` is the dotted path of this object ("" for the top level); `source` names the file.
  JsonObject(const nlohmann::json& j, std::string path, std::string source);

  bool has(const char* key) const { return j_.contains(key); }
  void read(const char* key, double& out);
  void read(const char* key, int& out);
  void read(const char* key, bool& out);
  void read(const char* key, std::string& out);
  void read(const char* key, Eigen::Vector2d& out);  // [x, y]
  void read(const char* key, Eigen::Vector4d& out);  // [a, b, c, d]
  void read(const char* key, Pose2& out);            // [x, y, theta]
  // A nested object (which must be an object); marks the key as known.
  JsonObject object(const char* key);
  // The raw value of a present key (marks it known), or nullptr when absent.
  const nlohmann::json* raw(const char* key);
  // Throws for the first key that was never read.
  void finish() const;

  std::string path_of(const std::string& key) const {
    return path_.empty() ? key : path_ + "." + key;
  }
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;
  const std::string& source() const { return source_; }

 private:
  const nlohmann::json& j_;
  std::string path_;
  std::string source_;
  std::set<std::string> known_;
};

// Reads an array of numbers of fixed size n into out[0..n); names `path` in errors.
void read_numbers(const nlohmann::json& v, double* out, std::size_t n, const std::string& path,
                  const std::string& source);

// Name of a JSON value's type for messages: "number", "string", "array"...
std::string json_type_name(const nlohmann::json& v);

// Parses JSON text; a syntax error becomes InputError(source, line, ...).
nlohmann::json parse_json_text(const std::string& text, const std::string& source);
// Reads and parses a JSON file; unreadable files throw InputError.
nlohmann::json read_json_file(const std::string& path);

}  // namespace locbench::sim
