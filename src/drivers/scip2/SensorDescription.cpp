#include "drivers/scip2/SensorDescription.hpp"

#include <cmath>
#include <cstdlib>

namespace uavslam::drivers::scip2 {
namespace {

constexpr double kTwoPi = 6.283185307179586;

// PP values are decimal text, possibly followed by a unit or comment ("SCAN:2400").
bool read_int(const InfoFields& fields, const std::string& key, int& value, std::string& problem) {
  const auto it = fields.find(key);
  if (it == fields.end()) {
    problem = "PP reply has no " + key;
    return false;
  }
  char* end = nullptr;
  const long number = std::strtol(it->second.c_str(), &end, 10);
  if (end == it->second.c_str()) {
    problem = "PP " + key + " is not a number: '" + it->second + "'";
    return false;
  }
  value = static_cast<int>(number);
  return true;
}

std::string field_or(const InfoFields& fields, const std::string& key, const std::string& other) {
  const auto it = fields.find(key);
  return it == fields.end() ? other : it->second;
}

}  // namespace

InfoFields parse_info_lines(const std::vector<std::string>& lines) {
  InfoFields fields;
  for (const std::string& line : lines) {
    const auto colon = line.find(':');
    if (colon == std::string::npos) continue;
    fields[line.substr(0, colon)] = line.substr(colon + 1);
  }
  return fields;
}

double SensorDescription::angle_increment() const {
  return kTwoPi / steps_per_turn;
}

double SensorDescription::angle_of_step(int step) const {
  return (step - front_step) * angle_increment();
}

double SensorDescription::scan_period() const {
  return 60.0 / motor_rpm;
}

std::optional<SensorDescription> describe_sensor(const InfoFields& parameters,
                                                 const InfoFields& version, std::string& problem) {
  SensorDescription d;
  if (!read_int(parameters, "DMIN", d.min_distance_mm, problem) ||
      !read_int(parameters, "DMAX", d.max_distance_mm, problem) ||
      !read_int(parameters, "ARES", d.steps_per_turn, problem) ||
      !read_int(parameters, "AMIN", d.first_step, problem) ||
      !read_int(parameters, "AMAX", d.last_step, problem) ||
      !read_int(parameters, "AFRT", d.front_step, problem) ||
      !read_int(parameters, "SCAN", d.motor_rpm, problem)) {
    return std::nullopt;
  }
  if (d.steps_per_turn <= 0 || d.motor_rpm <= 0 || d.first_step < 0 || d.last_step < d.first_step ||
      d.last_step >= d.steps_per_turn) {
    problem = "PP parameters are inconsistent (ARES " + std::to_string(d.steps_per_turn) +
              ", AMIN " + std::to_string(d.first_step) + ", AMAX " + std::to_string(d.last_step) +
              ", SCAN " + std::to_string(d.motor_rpm) + ")";
    return std::nullopt;
  }
  d.model = field_or(parameters, "MODL", field_or(version, "PROD", "unknown"));
  d.serial = field_or(version, "SERI", "");
  d.firmware = field_or(version, "FIRM", "");
  return d;
}

}  // namespace uavslam::drivers::scip2
