// Every parameter of the SLAM pipeline in one place, with the seed's values as defaults
// (thesis ch. 5.4.3). Loaded from YAML by io/SlamConfigFile; the core only reads it.
#pragma once

#include <array>
#include <string_view>
#include <utility>

namespace uavslam {

// Where the ICP starts (icp.motion_prior).
enum class MotionPrior {
  None,      // the last position: the seed, which has no motion model
  Odometry,  // the last position plus the odometry's motion since the previous posed scan
  Imu,       // the last position plus the IMU's accelerations integrated since (slam/InertialPrior)
};

// Where the heading comes from (icp.heading).
enum class HeadingMode {
  Source,         // the orientation source's yaw as it is (the seed)
  PeriodicCheck,  // the ICP also estimates yaw now and then and before keyframes (the seed's 5.6)
  EveryScan,      // the ICP estimates yaw with the translation in every scan
};

// The distance the ICP minimises (icp.metric).
enum class IcpMetric {
  PointToPoint,  // the seed, eq. 5.18
  PointToLine,   // to the wall through the map point, along its horizontal normal
};

// The nearest-neighbour search (nearest_neighbour.index).
enum class IndexKind {
  Exact,  // octree, exact answers
  Flann,  // the seed's approximate randomised kd-trees
  Brute,  // every point (reference)
};

// Each mode's spelling in the YAML file and on the command line, in one table per mode:
// io/SlamConfigFile parses with it and refuses any other word, naming these.
template <typename Mode>
struct ModeNames;
template <>
struct ModeNames<MotionPrior> {
  static constexpr std::array<std::pair<std::string_view, MotionPrior>, 3> all{
      {{"none", MotionPrior::None},
       {"odometry", MotionPrior::Odometry},
       {"imu", MotionPrior::Imu}}};
};
template <>
struct ModeNames<HeadingMode> {
  static constexpr std::array<std::pair<std::string_view, HeadingMode>, 3> all{
      {{"source", HeadingMode::Source},
       {"periodic_check", HeadingMode::PeriodicCheck},
       {"every_scan", HeadingMode::EveryScan}}};
};
template <>
struct ModeNames<IcpMetric> {
  static constexpr std::array<std::pair<std::string_view, IcpMetric>, 2> all{
      {{"point_to_point", IcpMetric::PointToPoint}, {"point_to_line", IcpMetric::PointToLine}}};
};
template <>
struct ModeNames<IndexKind> {
  static constexpr std::array<std::pair<std::string_view, IndexKind>, 3> all{
      {{"flann", IndexKind::Flann}, {"exact", IndexKind::Exact}, {"brute", IndexKind::Brute}}};
};

// The name of a mode as the YAML file spells it.
template <typename Mode>
constexpr std::string_view mode_name(Mode mode) {
  for (const auto& [name, value] : ModeNames<Mode>::all) {
    if (value == mode) return name;
  }
  return "?";
}

struct SlamConfig {
  // Step 1-2: which points of a scan take part.
  struct Scan {
    int subsample_every = 5;  // keep every k-th valid point (seed: 216 of 1080)
    // Beyond the seed: m; a level beam's point less than this above the floor's level, as the
    // floor beams measure it, struck the floor from a tilted scanner and is set aside
    // (extensions/FloorReturns). 0: every point kept, as the seed.
    double floor_margin = 0.0;
    // Beyond the seed: each beam placed from where the body was when it fired (the geometry's
    // fire times), by the IMU's rate and the motion prior's velocity (ScanProjection's
    // SweepMotion). false: every beam from the pose at the stamp, as the seed.
    bool deskew = false;
  } scan;

  // Beyond the seed: the height from the floor's level (extensions/FloorLevel), for a scanner
  // with floor beams. m; > 0: a floor seen within this of the level taken over the first
  // level_window seconds is that floor, and measures the height (0: the height is the match's
  // alone, chained over floor the map has not seen, as the seed).
  struct Floor {
    double level_gate = 0.0;
    double level_window = 1.0;  // s, from the first scan that sees the floor
    double flatness = 0.01;     // m; how far a floor's level differs from place to place (sigma)
  } floor;

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
    // Where the ICP starts. The caller that owns the odometry supplies the motion
    // (slam/VehicleSlam); the core only adds it (SlamPipeline::process_scan).
    MotionPrior motion_prior = MotionPrior::None;
    // Where the heading comes from (beyond the seed, which trusts the orientation source). With
    // PeriodicCheck, every heading_check_every scans and before each keyframe the ICP also
    // estimates yaw and corrects the heading when it disagrees by more than
    // heading_check_tolerance.
    HeadingMode heading = HeadingMode::Source;
    int heading_check_every = 10;           // scans between periodic checks
    double heading_check_tolerance = 0.01;  // rad; a smaller disagreement leaves the heading alone
    // s; > 0 with EveryScan: the map's heading, first set by one sample of the source's, is turned
    // once, this long after the first scan, onto the source's heading averaged over every scan
    // matched meanwhile (0: the first sample's, as before).
    double heading_anchor = 0.0;
    // rad; > 0 with EveryScan: a scan from a scanner tilted further from level matches the
    // translation only, the heading staying the source's with the correction so far (0: no
    // limit).
    double heading_max_tilt = 0.0;
    double max_rotation = 0.35;  // rad; a larger yaw correction in one scan discards the scan
    // The distance the ICP minimises; point-to-line has no bias from the map's point spacing.
    IcpMetric metric = IcpMetric::PointToPoint;
    // How firmly the rotation-aware or point-to-line ICP holds its predicted start, as a fraction
    // of the information the scan gives (PlanarCorrection): what the scan cannot see stays as
    // predicted. The seed's translation-only step has no such term.
    double prior_weight = 0.001;
    // m; > 0: after the ICP converged, up to refine_iterations more iterations weigh each pair
    // by the Cauchy kernel of this scale (PlanarCorrection), settling the scan on the pairs that
    // agree with it (0 = no refinement).
    double robust_scale = 0.0;
    int refine_iterations = 5;
    // Point-to-line: the refinement, and the error and pairs the match reports, leave out the
    // pairs whose map point has no wall normal (drop_pairs_without_normal); false: they count
    // point to point throughout.
    bool refine_lines_only = false;
    // m (and rad); stop the ICP early once a step is smaller (0 = never: the seed's fixed count).
    double stop_step = 0.0;
    // Beyond the seed: a match whose position differs from the motion prior's prediction, in the
    // directions the scan fixed, by more than this many standard deviations of the two together
    // (a Mahalanobis distance) is rejected as disagreeing with the prior (0: no such check, as the
    // seed; needs a motion prior with a covariance and degeneracy.threshold > 0, which gives the
    // match its covariance).
    double prior_gate = 0.0;
    // Matches rejected by the gate in a row, each agreeing with the one before, after which the
    // next such match is taken: the prior, not the scans, has drifted (0: never; PriorGate).
    int prior_gate_overrule = 3;
  } icp;

  // The nearest-neighbour search: FLANN approximate kd-trees (real time) or exact (reference).
  struct NearestNeighbour {
    // Exact: measured 15x faster than FLANN's kd-trees here (docs/speed.md).
    IndexKind index = IndexKind::Exact;
    int flann_trees = 4;    // randomised kd-trees
    int flann_checks = 32;  // leaves visited per query: the accuracy/speed knob
  } nearest_neighbour;

  // Step 6: when the aligned scan is added to the world map.
  struct Map {
    double keyframe_height = 0.2;   // m of vertical motion since the last map update
    double keyframe_lateral = 0.5;  // m of horizontal motion since the last map update
    int subsample_every = 5;  // a keyframe adds every k-th valid point (seed: the matched m_i)
    // rad of heading change since the last map update that also makes a keyframe (0: never, as
    // the seed, whose heading is not its own). A robot turning on the spot sees new walls.
    double keyframe_rotation = 0.0;
    // m; a keyframe point this close to a map point is not added (0: keep all, as the seed): a
    // place is mapped once, and the map is bounded by the size of the place, not the flight.
    double min_point_spacing = 0.0;
  } map;

  // Beyond the seed: after a gap in the scans longer than `gap` (a link outage, a dropout) the
  // last position is stale, and the ICP is started from a grid of positions over the disc the
  // vehicle can have covered (core/Relocalisation). Inert while scans come at the sensor's rate.
  struct Recovery {
    double gap = 0.5;         // s without a scan that makes the last position stale (0: never)
    double max_speed = 2.0;   // m/s; the disc's radius is max_speed x gap ...
    double max_radius = 3.0;  // m; ... at most this
    double grid_step = 0.5;   // m between starts: under twice the pairing gate, so one converges
  } recovery;

  // Beyond the seed: what moves (core/extensions/FreeSpace). A scan point where earlier beams saw
  // empty space, with nothing that stood there from the first within the ICP's pairing gate, is a
  // person or a thing that came there: it is left out of the match and the map. The grid is of the
  // scanner's slab of the building (its height, give or take 0.3 m): a 2D log's plane, a UAV's
  // level beams.
  struct FreeSpaceOptions {
    bool enabled = false;
    double resolution = 0.1;  // m, the grid's cells
    double reach = 7.0;       // m: a beam marks the space free this far at most
    int min_passes = 2;       // beams through a cell before anything was seen in it: it was empty
    double memory = 10.0;     // s: only what the beams saw this lately (the map's frame drifts)
  } free_space;

  // Beyond the seed: what the scan can see (core/extensions/ScanInformation). A direction whose
  // information fraction is under `threshold` is degenerate: the pose keeps the motion prior's
  // position along it instead of the match's, and the report says so.
  struct Degeneracy {
    double threshold = 0.0;   // 0: no analysis (the seed trusts every match in every direction)
    double min_sigma = 0.01;  // m; the pairs' residual spread is taken as at least this
    // The horizontal direction left blind searched for a structure that fixes it
    // (extensions/BlindDirectionSearch): over the prior's 3 sigma, at most this far either way
    // (m; 0 = never searched: the prior keeps it).
    double search_window = 0.0;
    double search_step = 0.02;       // m between the shifts searched
    double search_sigma = 0.02;      // m: a fix's error is taken as at least this
    double search_uniqueness = 0.5;  // another minimum's depth over the fix's, at most
    // A yaw the scan cannot see (its information fraction with the translation free under
    // `threshold`: a round room) is held at the prediction's and the scan matched again
    // (SlamPipeline::yaw_blind); only with the yaw estimated and the analysis on.
    bool hold_blind_yaw = true;
  } degeneracy;

  // The motion prior's noise (icp.motion_prior imu or odometry): how fast its uncertainty grows.
  struct Motion {
    // IMU: white noise of the specific force, m/s^2/sqrt(Hz) (the datasheet's noise density,
    // with the attitude's noise folded in: a tilt error of theta leaks g theta).
    double accel_noise_density = 0.003;
    double accel_bias_walk = 1e-4;     // m/s^3/sqrt(Hz): how fast the bias may wander
    double initial_speed_sigma = 0.1;  // m/s at the first scan (0.1: starting at rest)
    double initial_bias_sigma = 0.05;  // m/s^2: the accelerometer's bias before any match
    // The IMU prior's filter holds the horizontal part of a match's error that the matches around
    // it share (m, 1 sigma: the few structures that fix a weak direction, each placed in the map
    // from a handful of returns), changing over match_error_distance (m) flown: the map under the
    // scan is another one. 0: the matches' errors are taken as independent.
    double match_error_sigma = 0.0;
    double match_error_distance = 0.5;
    double odometry_noise_per_metre = 0.1;  // m of odometry error per m travelled
    double odometry_noise_floor = 0.002;    // m per scan, however short the motion
    // The IMU prior fuses a velocity source's samples when they come (VelocitySample): where the
    // scan is blind, the position then drifts with the velocity's noise, not the accelerometer
    // bias's square of time.
    bool fuse_velocity = false;
  } motion;

  // Orientation source: how far apart the IMU samples around a scan may be.
  struct Imu {
    double max_gap = 0.1;  // s; a scan with no IMU sample this close is dropped
    // rad, 1 sigma: how well the source knows the attitude, as the pose's covariance states it
    // (the matcher takes roll and pitch from the source, and the heading unless it corrects it).
    double attitude_sigma = 0.0175;  // roll and pitch: an autopilot's attitude, about 1 degree
    double heading_sigma = 0.035;    // yaw: about 2 degrees
    // rad/s, 1 sigma: how fast the source's heading may drift (its gyro's bias), the prior of the
    // drift that heading checks learn and correct for (extensions/HeadingRate); 0: none is learnt
    // (the seed takes the source as it is).
    double heading_drift_sigma = 0.0;
  } imu;

  // Beyond the seed: the pose-graph back end (src/backend/KeyframeGraph). Keyframes become the
  // nodes of a graph, each new one is searched against older ones for a loop, and an accepted loop
  // moves the keyframes and the map with them. Off: the seed's one ever-growing map.
  struct LoopClosure {
    bool enabled = false;
    // How far two successive keyframes are known from each other (the front end's chain), 1 sigma:
    double step_sigma = 0.01;                 // m, however short the step
    double step_sigma_per_metre = 0.02;       // m per m between them
    double step_yaw_sigma = 0.002;            // rad, however small the turn
    double step_yaw_sigma_per_radian = 0.02;  // rad per rad turned
    // How well a verified loop fixes the two keyframes, 1 sigma.
    double loop_sigma = 0.05;      // m
    double loop_yaw_sigma = 0.02;  // rad
    // The search: keyframes this far back along the flight (m) are candidates ...
    double min_travel = 10.0;
    // ... within a window of 3 sigma of the chain between them, at least min_radius and
    // at most max_radius (m) wide each way, and at most pi in yaw.
    double min_radius = 1.0;
    double max_radius = 8.0;
    // A keyframe the graph already places within this of the newest (3 sigma) is not searched:
    // the front end's matching holds about that much, twice its pairing gate (m; 0 = search
    // every candidate).
    double known_radius = 0.5;
    int max_candidates = 2;    // searched per new keyframe, the nearest first
    int submap_keyframes = 5;  // either side of a candidate: its neighbourhood is the reference
    double resolution = 0.05;  // m, the correlative matcher's finest grid
    // Verification: the share of the new keyframe's points on the candidate's surfaces ...
    double min_score = 0.55;
    // ... and by how much the best pose beats the best other one at least ambiguity_radius away
    // (a corridor whose doors repeat has two).
    double min_score_margin = 0.05;
    double ambiguity_radius = 0.5;  // m
    // ... and the surfaces it lays on each other seen from the same side: at most this share of
    // the paired points with normals face each other, nor of those that fix the direction the
    // others fix least (backend/SurfaceSides; 1 = not checked).
    double max_opposed_share = 0.5;
  } loop_closure;
};

}  // namespace uavslam
