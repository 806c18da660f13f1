// What a SCIP 2.0 sensor says about itself (C-42-03320B section 8: VV "version", PP "parameters",
// II "state"; each data line is "KEY:VALUE") and the scan geometry that follows from it
// (section 5, "Measurement Direction and Points": step s points at (s - AFRT) * 360 deg / ARES,
// counter-clockwise seen from above, so the measurable steps AMIN..AMAX span the field of view).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace uavslam::drivers::scip2 {

// The KEY:VALUE lines of a VV, PP or II reply.
using InfoFields = std::map<std::string, std::string>;
InfoFields parse_info_lines(const std::vector<std::string>& lines);

struct SensorDescription {
  std::string model;        // PP MODL (or VV PROD)
  std::string serial;       // VV SERI
  std::string firmware;     // VV FIRM
  int min_distance_mm = 0;  // PP DMIN
  int max_distance_mm = 0;  // PP DMAX
  int steps_per_turn = 0;   // PP ARES: steps in 360 deg
  int first_step = 0;       // PP AMIN
  int last_step = 0;        // PP AMAX
  int front_step = 0;       // PP AFRT: the step on the sensor's x axis
  int motor_rpm = 0;        // PP SCAN: one scan per revolution

  int beams() const { return last_step - first_step + 1; }
  double angle_increment() const;        // rad per step
  double angle_of_step(int step) const;  // rad from the x axis, counter-clockwise
  double scan_period() const;            // s
};

// The description from a PP reply's fields (and VV's, for serial and firmware); nullopt with
// `problem` set when a needed field is missing or not a number.
std::optional<SensorDescription> describe_sensor(const InfoFields& parameters,
                                                 const InfoFields& version, std::string& problem);

}  // namespace uavslam::drivers::scip2
