// A small reader over yaml-cpp for configuration files that fails loudly and precisely: every
// problem is a ConfigError naming the file, the key path (e.g. `lidar.mount.rpy_deg[2]`), the
// offending value and what was expected. Unknown keys are errors, so typos cannot pass silently.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "core/Types.hpp"

namespace uavslam::io {

class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The values a number may take; describe() words it for messages ("> 0", "in [0, 360]").
struct NumberRange {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_exclusive = false;

  static NumberRange any() { return {}; }
  static NumberRange positive() { return {0.0, std::numeric_limits<double>::infinity(), true}; }
  static NumberRange non_negative() { return at_least(0.0); }
  static NumberRange at_least(double low) { return {low, std::numeric_limits<double>::infinity()}; }
  static NumberRange greater_than(double low) {
    return {low, std::numeric_limits<double>::infinity(), true};
  }
  static NumberRange between(double low, double high) { return {low, high}; }

  bool contains(double value) const;
  std::string describe() const;  // empty when any number will do
};

// One node of a parsed YAML document together with where it came from.
class YamlReader {
 public:
  // Parses a whole file; `kind` names it in errors: "cannot read <kind> file '<path>': <why>".
  static YamlReader from_file(const std::string& path, const std::string& kind);
  // Parses `text` as the value found at `key_path`; `source` stands in for the file name in
  // errors (e.g. a command-line option).
  static YamlReader from_text(const std::string& text, const std::string& source,
                              const std::string& key_path);

  const std::string& source() const { return source_; }
  const std::string& key_path() const { return key_path_; }

  // Mappings (an empty document counts as an empty mapping).
  bool has(const std::string& key) const;
  YamlReader at(const std::string& key) const;  // missing -> "missing required key 'a.b'"
  std::optional<YamlReader> find(const std::string& key) const;
  // Every key must be one of `allowed` and appear once: "unknown key 'icp.iteratons'".
  void expect_keys_only(const std::vector<std::string>& allowed) const;

  // Sequences.
  std::vector<YamlReader> elements() const;

  // Scalars, each checked for type (and range where given).
  double as_double(const NumberRange& range = NumberRange::any()) const;
  int as_int(const NumberRange& range = NumberRange::any()) const;
  std::uint64_t as_uint64() const;
  bool as_bool() const;
  std::string as_string() const;
  std::string as_choice(const std::vector<std::string>& allowed) const;
  Vec3 as_vec3() const;             // [x, y, z]
  Eigen::Vector2d as_vec2() const;  // [x, y]

  // Required values of a mapping's keys.
  double get_double(const std::string& key, const NumberRange& range = NumberRange::any()) const;
  int get_int(const std::string& key, const NumberRange& range = NumberRange::any()) const;
  bool get_bool(const std::string& key) const;
  std::string get_string(const std::string& key) const;
  Vec3 get_vec3(const std::string& key) const;

  // Optional values: `fallback` when the key is absent (a present key is still fully checked).
  double get_double_or(const std::string& key, double fallback,
                       const NumberRange& range = NumberRange::any()) const;
  int get_int_or(const std::string& key, int fallback,
                 const NumberRange& range = NumberRange::any()) const;
  std::uint64_t get_uint64_or(const std::string& key, std::uint64_t fallback) const;
  bool get_bool_or(const std::string& key, bool fallback) const;
  std::string get_string_or(const std::string& key, const std::string& fallback) const;
  Vec3 get_vec3_or(const std::string& key, const Vec3& fallback) const;

  // "<source>: key '<path>': expected <expected>, got '<value>'".
  [[noreturn]] void fail_expected(const std::string& expected) const;
  // "<source>: key '<path>': <problem>".
  [[noreturn]] void fail(const std::string& problem) const;

 private:
  YamlReader(YAML::Node node, std::string source, std::string key_path, bool from_file);
  YamlReader child(const YAML::Node& node, const std::string& path) const;
  std::string child_path(const std::string& key) const;
  void expect_mapping() const;
  std::vector<double> as_numbers(std::size_t count, const std::string& shape) const;
  [[noreturn]] void fail_at(const YAML::Mark& mark, const std::string& message) const;

  YAML::Node node_;
  std::string source_;
  std::string key_path_;
  bool from_file_;  // marks are file lines (not positions in a command-line value)
};

}  // namespace uavslam::io
