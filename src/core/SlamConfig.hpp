// Every parameter of the SLAM pipeline in one place, with the seed's values as defaults
// (thesis ch. 5.4.3). Loaded from YAML by io/SlamConfigFile; the core only reads it.
#pragma once

#include <string>

namespace uavslam {

struct SlamConfig {
  // Step 1-2: which points of a scan take part.
  struct Scan {
    int subsample_every = 5;  // keep every k-th valid point (seed: 216 of 1080)
  } scan;

  // Step 3-5: the translation-only ICP (Figure 5.15).
  struct Icp {
    int iterations = 10;            // fixed count, no convergence test (seed 5.4.3.2)
    double max_translation = 1.0;   // m; a larger accumulated correction discards the scan
    double max_error_after = 0.05;  // m^2; E(t) after alignment above this = wrong match
    double max_error_ratio = 1.2;   // E_after / E_before above this = alignment made it worse
    double max_correspondence_distance = 0.3;  // m; farther pairs get omega = 0 (0: keep all)
    // Per-axis weights of eq. 5.17: level beams inform x-y, floor/ceiling beams z (a planar scan
    // sees height only through beams a mirror deflects). false: every pair informs every axis.
    bool split_axes = true;
    // Where the ICP starts: "none" = the last position (the seed: no motion model) | "odometry" =
    // the last position plus the odometry's motion since the previous scan. The caller that owns
    // the odometry supplies the motion (SlamPipeline::process_scan); the core only adds it.
    std::string motion_prior = "none";
  } icp;

  // The nearest-neighbour search: FLANN approximate kd-trees (real time) or exact (reference).
  struct NearestNeighbour {
    // "exact" (octree; measured 15x faster than FLANN's kd-trees here, README) | "flann" (the
    // seed's approximate search) | "brute" (reference)
    std::string index = "exact";
    int flann_trees = 4;    // randomised kd-trees
    int flann_checks = 32;  // leaves visited per query: the accuracy/speed knob
  } nearest_neighbour;

  // Step 6: when the aligned scan is added to the world map.
  struct Map {
    double keyframe_height = 0.2;   // m of vertical motion since the last map update
    double keyframe_lateral = 0.5;  // m of horizontal motion since the last map update
    int subsample_every = 5;  // a keyframe adds every k-th valid point (seed: the matched m_i)
  } map;

  // Orientation source: how far apart the IMU samples around a scan may be.
  struct Imu {
    double max_gap = 0.1;  // s; a scan with no IMU sample this close is dropped
  } imu;
};

}  // namespace uavslam
