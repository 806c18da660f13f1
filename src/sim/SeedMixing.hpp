// Independent random streams from one scenario seed, and the noise drawn from them: each simulator
// mixes in its own constant, so the LiDAR and the IMU never share (or shift) each other's random
// numbers.
#pragma once

#include <cstdint>
#include <random>

#include "core/Types.hpp"

namespace uavslam::sim {

constexpr std::uint64_t kLidarStream = 0x4c494441522d3031ULL;     // "LIDAR-01"
constexpr std::uint64_t kImuStream = 0x494d552d2d2d3031ULL;       // "IMU---01"
constexpr std::uint64_t kVelocityStream = 0x56454c2d2d2d3031ULL;  // "VEL---01"
constexpr std::uint64_t kOdometryStream = 0x4f444f4d2d2d3031ULL;  // "ODOM--01"

// splitmix64 of seed ^ stream: nearby seeds give unrelated generator states.
constexpr std::uint64_t mix_seed(std::uint64_t seed, std::uint64_t stream) {
  std::uint64_t z = (seed ^ stream) + 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// Three standard normals of one stream, drawn for x, y and z in that order (separate statements:
// the order of evaluation inside one expression is unspecified).
inline Vec3 standard_normal_vector(std::mt19937_64& random,
                                   std::normal_distribution<double>& standard_normal) {
  const double x = standard_normal(random);
  const double y = standard_normal(random);
  const double z = standard_normal(random);
  return {x, y, z};
}

}  // namespace uavslam::sim
