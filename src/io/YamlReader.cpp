#include "io/YamlReader.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <utility>

namespace uavslam::io {

namespace {

constexpr std::size_t kShownValueLength = 80;  // longer values are cut in messages

std::string shown_value(const YAML::Node& node) {
  if (!node.IsDefined() || node.IsNull()) return "nothing";
  std::string text;
  if (node.IsScalar()) {
    text = node.Scalar();
  } else {  // one line, whatever style the file used
    YAML::Node copy = YAML::Clone(node);
    copy.SetStyle(YAML::EmitterStyle::Flow);
    YAML::Emitter flow;
    flow << copy;
    text = flow.c_str();
    std::replace(text.begin(), text.end(), '\n', ' ');
  }
  if (text.size() > kShownValueLength) text = text.substr(0, kShownValueLength) + "...";
  return "'" + text + "'";
}

std::string joined(const std::vector<std::string>& words, const std::string& quote) {
  std::string text;
  for (const std::string& word : words) {
    text += (text.empty() ? "" : ", ") + quote + word + quote;
  }
  return text;
}

std::string number_text(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

YAML::Node parse_file(const std::string& path, const std::string& kind) {
  const std::string prefix = "cannot read " + kind + " file '" + path + "': ";
  std::error_code ignored;
  if (std::filesystem::is_directory(path, ignored)) throw ConfigError(prefix + "is a directory");
  std::ifstream in(path);
  if (!in) throw ConfigError(prefix + std::strerror(errno));
  try {
    return YAML::Load(in);
  } catch (const YAML::Exception& e) {
    std::ostringstream reason;
    if (!e.mark.is_null()) {
      reason << "line " << e.mark.line + 1 << ", column " << e.mark.column + 1 << ": ";
    }
    reason << e.msg;
    throw ConfigError(prefix + reason.str());
  }
}

}  // namespace

bool NumberRange::contains(double value) const {
  const bool above_min = min_exclusive ? value > min : value >= min;
  return above_min && value <= max;
}

std::string NumberRange::describe() const {
  const bool has_min = std::isfinite(min);
  const bool has_max = std::isfinite(max);
  if (has_min && has_max) {
    return std::string("in ") + (min_exclusive ? "(" : "[") + number_text(min) + ", " +
           number_text(max) + "]";
  }
  if (has_min) return (min_exclusive ? "> " : ">= ") + number_text(min);
  if (has_max) return "<= " + number_text(max);
  return "";
}

YamlReader::YamlReader(YAML::Node node, std::string source, std::string key_path, bool from_file)
    : node_(std::move(node)),
      source_(std::move(source)),
      key_path_(std::move(key_path)),
      from_file_(from_file) {}

YamlReader YamlReader::from_file(const std::string& path, const std::string& kind) {
  return YamlReader(parse_file(path, kind), path, "", true);
}

YamlReader YamlReader::from_text(const std::string& text, const std::string& source,
                                 const std::string& key_path) {
  try {
    return YamlReader(YAML::Load(text), source, key_path, false);
  } catch (const YAML::Exception& e) {
    throw ConfigError(source + ": key '" + key_path + "': cannot parse '" + text + "': " + e.msg);
  }
}

std::string YamlReader::child_path(const std::string& key) const {
  return key_path_.empty() ? key : key_path_ + "." + key;
}

YamlReader YamlReader::child(const YAML::Node& node, const std::string& path) const {
  return YamlReader(node, source_, path, from_file_);
}

void YamlReader::fail_at(const YAML::Mark& mark, const std::string& message) const {
  std::ostringstream text;
  text << source_ << ": " << message;
  if (from_file_ && !mark.is_null()) {
    text << " (line " << mark.line + 1 << ", column " << mark.column + 1 << ")";
  }
  throw ConfigError(text.str());
}

void YamlReader::fail(const std::string& problem) const {
  const std::string where = key_path_.empty() ? "top level" : "key '" + key_path_ + "'";
  fail_at(node_.Mark(), where + ": " + problem);
}

void YamlReader::fail_expected(const std::string& expected) const {
  fail("expected " + expected + ", got " + shown_value(node_));
}

void YamlReader::expect_mapping() const {
  if (!node_.IsNull() && !node_.IsMap()) fail_expected("a mapping of keys to values");
}

bool YamlReader::has(const std::string& key) const {
  return find(key).has_value();
}

std::optional<YamlReader> YamlReader::find(const std::string& key) const {
  expect_mapping();
  if (node_.IsNull()) return std::nullopt;
  const YAML::Node value = node_[key];
  if (!value.IsDefined()) return std::nullopt;
  return child(value, child_path(key));
}

YamlReader YamlReader::at(const std::string& key) const {
  std::optional<YamlReader> value = find(key);
  if (!value) fail_at(node_.Mark(), "missing required key '" + child_path(key) + "'");
  return *value;
}

void YamlReader::expect_keys_only(const std::vector<std::string>& allowed) const {
  expect_mapping();
  if (node_.IsNull()) return;
  std::set<std::string> seen;
  for (const auto& entry : node_) {
    const std::string key = entry.first.IsScalar() ? entry.first.Scalar() : "";
    const std::string path = child_path(key);
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
      fail_at(entry.first.Mark(),
              "unknown key '" + path + "' (allowed keys: " + joined(allowed, "") + ")");
    }
    if (!seen.insert(key).second) fail_at(entry.first.Mark(), "duplicate key '" + path + "'");
  }
}

std::vector<YamlReader> YamlReader::elements() const {
  if (node_.IsNull()) return {};  // an empty `boxes:` is an empty list
  if (!node_.IsSequence()) fail_expected("a list");
  std::vector<YamlReader> items;
  for (std::size_t i = 0; i < node_.size(); ++i) {
    items.push_back(child(node_[i], key_path_ + "[" + std::to_string(i) + "]"));
  }
  return items;
}

double YamlReader::as_double(const NumberRange& range) const {
  const std::string expected =
      "a number" + (range.describe().empty() ? "" : " " + range.describe());
  if (!node_.IsScalar()) fail_expected(expected);
  double value = 0.0;
  try {
    value = node_.as<double>();
  } catch (const YAML::BadConversion&) {
    fail_expected(expected);
  }
  if (!std::isfinite(value) || !range.contains(value)) fail_expected(expected);
  return value;
}

int YamlReader::as_int(const NumberRange& range) const {
  const std::string expected =
      "an integer" + (range.describe().empty() ? "" : " " + range.describe());
  if (!node_.IsScalar()) fail_expected(expected);
  long long value = 0;
  try {
    value = node_.as<long long>();  // rejects "2.5": an int must be written as one
  } catch (const YAML::BadConversion&) {
    fail_expected(expected);
  }
  const bool fits =
      value >= std::numeric_limits<int>::min() && value <= std::numeric_limits<int>::max();
  if (!fits || !range.contains(static_cast<double>(value))) fail_expected(expected);
  return static_cast<int>(value);
}

std::uint64_t YamlReader::as_uint64() const {
  const std::string expected = "a non-negative integer";
  if (!node_.IsScalar()) fail_expected(expected);
  try {
    return node_.as<std::uint64_t>();
  } catch (const YAML::BadConversion&) {
    fail_expected(expected);
  }
}

bool YamlReader::as_bool() const {
  if (!node_.IsScalar()) fail_expected("true or false");
  try {
    return node_.as<bool>();
  } catch (const YAML::BadConversion&) {
    fail_expected("true or false");
  }
}

std::string YamlReader::as_string() const {
  if (!node_.IsScalar()) fail_expected("a string");
  return node_.Scalar();
}

std::string YamlReader::as_choice(const std::vector<std::string>& allowed) const {
  const std::string expected = "one of " + joined(allowed, "'");
  if (!node_.IsScalar()) fail_expected(expected);
  const std::string value = node_.Scalar();
  if (std::find(allowed.begin(), allowed.end(), value) == allowed.end()) fail_expected(expected);
  return value;
}

std::vector<double> YamlReader::as_numbers(std::size_t count, const std::string& shape) const {
  if (!node_.IsSequence() || node_.size() != count) {
    fail_expected("a list of " + std::to_string(count) + " numbers " + shape);
  }
  std::vector<double> numbers;
  for (const YamlReader& item : elements()) numbers.push_back(item.as_double());
  return numbers;
}

Vec3 YamlReader::as_vec3() const {
  const std::vector<double> xyz = as_numbers(3, "[x, y, z]");
  return {xyz[0], xyz[1], xyz[2]};
}

Eigen::Vector2d YamlReader::as_vec2() const {
  const std::vector<double> xy = as_numbers(2, "[x, y]");
  return {xy[0], xy[1]};
}

double YamlReader::get_double(const std::string& key, const NumberRange& range) const {
  return at(key).as_double(range);
}

int YamlReader::get_int(const std::string& key, const NumberRange& range) const {
  return at(key).as_int(range);
}

bool YamlReader::get_bool(const std::string& key) const {
  return at(key).as_bool();
}

std::string YamlReader::get_string(const std::string& key) const {
  return at(key).as_string();
}

Vec3 YamlReader::get_vec3(const std::string& key) const {
  return at(key).as_vec3();
}

double YamlReader::get_double_or(const std::string& key, double fallback,
                                 const NumberRange& range) const {
  const std::optional<YamlReader> value = find(key);
  return value ? value->as_double(range) : fallback;
}

int YamlReader::get_int_or(const std::string& key, int fallback, const NumberRange& range) const {
  const std::optional<YamlReader> value = find(key);
  return value ? value->as_int(range) : fallback;
}

std::uint64_t YamlReader::get_uint64_or(const std::string& key, std::uint64_t fallback) const {
  const std::optional<YamlReader> value = find(key);
  return value ? value->as_uint64() : fallback;
}

bool YamlReader::get_bool_or(const std::string& key, bool fallback) const {
  const std::optional<YamlReader> value = find(key);
  return value ? value->as_bool() : fallback;
}

std::string YamlReader::get_string_or(const std::string& key, const std::string& fallback) const {
  const std::optional<YamlReader> value = find(key);
  return value ? value->as_string() : fallback;
}

Vec3 YamlReader::get_vec3_or(const std::string& key, const Vec3& fallback) const {
  const std::optional<YamlReader> value = find(key);
  return value ? value->as_vec3() : fallback;
}

}  // namespace uavslam::io
