// The whole real-time SLAM of the seed for one vehicle, scan by scan (thesis Figure 5.15):
// orientation from the IMU at the scan's time, translation from the scan matcher against the
// world map, keyframes into the map after enough motion. The matcher process and the offline
// tools run this same object; it knows nothing of DDS, files or clocks.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <utility>

#include "core/Heading.hpp"
#include "core/ImuBuffer.hpp"
#include "core/MotionPrediction.hpp"
#include "core/ScanMatcher.hpp"
#include "core/ScanOutcome.hpp"
#include "core/ScanProjection.hpp"
#include "core/SlamConfig.hpp"
#include "core/WorldMap.hpp"
#include "core/extensions/BlindDirectionSearch.hpp"
#include "core/extensions/FloorLevel.hpp"
#include "core/extensions/FreeSpace.hpp"
#include "core/extensions/HeadingAnchor.hpp"
#include "core/extensions/HeadingRate.hpp"
#include "core/extensions/MapUncertainty.hpp"
#include "core/extensions/MatchNoise.hpp"
#include "core/extensions/PriorAgreement.hpp"
#include "core/extensions/ScanInformation.hpp"

namespace uavslam {

// The map's frame turned by `yaw` rad about the vertical through `origin` (extensions/
// HeadingAnchor): every map point, keyframe and the pose moved by transform().
struct FrameTurn {
  Vec3 origin = Vec3::Zero();
  double yaw = 0.0;
  Eigen::Isometry3d transform() const {
    return Eigen::Translation3d(origin) * yaw_rotation(yaw) * Eigen::Translation3d(-origin);
  }
};

struct ScanReport {
  ScanOutcome outcome = ScanOutcome::Malformed;
  Pose pose;                    // the vehicle's pose after this scan (unchanged if rejected)
  std::size_t points_used = 0;  // after subsampling
  std::size_t invalid_ranges = 0;
  std::size_t floor_returns = 0;  // level beams' points set aside as floor strikes (FloorReturns)
  // Points set aside where earlier beams saw empty space: what moved there (free_space.enabled,
  // extensions/FreeSpace).
  std::size_t moving_points = 0;
  // How the body moved while the scanner swept, as the points were placed (scan.deskew; zero:
  // every beam from the pose at the stamp). Whoever places the scan again (the dense products)
  // places it alike.
  SweepMotion sweep;
  double error_before = 0.0;  // m^2, eq. 5.18
  double error_after = 0.0;   // m^2
  int iterations = 0;
  bool map_updated = false;  // this scan was a keyframe
  // The match failed and the pose is the predicted one (the last pose moved by the motion prior):
  // the vehicle went where the other source says, not where it was.
  bool dead_reckoned = false;
  // The height was measured from the floor's level (floor.level_gate, extensions/FloorLevel).
  bool height_from_floor = false;
  // After a gap in the scans the ICP searched a grid of starts (core/Relocalisation).
  bool relocalised = false;
  // The scan could not see its yaw (a turn and a shift alike to it): matched again with the
  // heading the prediction gave (SlamPipeline::yaw_blind).
  bool yaw_held = false;
  std::size_t map_size = 0;
  Points added_points;  // what this scan added to the map (empty unless map_updated)
  // Beyond the seed (degeneracy.threshold > 0): what the scan saw of each direction, and the
  // pose's covariance: the match's in the directions it fixed, the motion prior's in the others.
  Observability seen;
  // The direction the scan left blind was searched and a structure across it fixed it
  // (degeneracy.search_window; extensions/BlindDirectionSearch): `seen` counts it as seen.
  bool blind_fixed = false;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  // m^2, of pose.position in the map
  // m^2: how well the map points the match paired with are placed (extensions/MapUncertainty);
  // for a pose carried by the prior, the last match's; with `covariance` turned by the map's
  // heading error (SlamPipeline::map_covariance).
  Eigen::Matrix3d map_covariance = Eigen::Matrix3d::Zero();
  // The match's distance from the motion prior's prediction, in standard deviations
  // (extensions/PriorAgreement); 0 without a prior that has a covariance.
  double prior_distance = 0.0;
  // The gate had turned away the matches before this one, each agreeing with the last, and this
  // one, agreeing with them, was taken against the prior (icp.prior_gate_overrule).
  bool prior_overruled = false;
  // After this scan the map's frame was turned onto the source's heading (icp.heading_anchor):
  // this report (pose, added_points) and the map are in the turned frame, the reports before in
  // the old one.
  std::optional<FrameTurn> frame_turn;

  // The pose's covariance in the map's frame as a whole (from the take-off point): the match's
  // relative to the map, and the map's own. What goes to those who fly on the pose.
  Eigen::Matrix3d absolute_covariance() const { return covariance + map_covariance; }

  bool accepted() const {
    return outcome == ScanOutcome::Accepted || outcome == ScanOutcome::MapInitialised;
  }
};

// A keyframe's share of the map, for rebuilding it (replace_map): its points and, with the
// point-to-line metric, their normals (else empty), world frame.
struct MapKeyframe {
  Vec3 position = Vec3::Zero();  // of the body when the keyframe was taken
  Points points;
  std::vector<Vec3> normals;
  double turn = 0.0;  // rad: how far its heading turned about the vertical
};

class SlamPipeline {
 public:
  // initial_position: where the body is when the first scan arrives (e.g. the take-off point).
  explicit SlamPipeline(const SlamConfig& config, const Vec3& initial_position = Vec3::Zero());

  // Where the body is at the first scan, when known only after construction (a log's first
  // scan); before the first scan.
  void start_at(const Vec3& position) { pose_.position = position; }

  void add_imu(const ImuSample& sample);
  // prediction: the body's translation since the previous scan as another source predicts it
  // (wheel odometry, the IMU's accelerations), in the frame of the orientation source; the ICP
  // starts from the last position plus it (turned by the heading correction, if any). None (the
  // default) is the seed, which has no motion model.
  ScanReport process_scan(const Scan& scan, const MotionPrediction& prediction = {});

  // Beyond the seed (the pose-graph back end, loop_closure): the map rebuilt from its keyframes,
  // one per keyframe made so far and in that order, where an optimisation moved them; the vehicle
  // moves with the newest one: `correction` takes the old map frame to the new, a turn of `yaw`
  // rad about the vertical and a shift (keyframe_starts() then indexes the new map). Throws
  // std::invalid_argument for another keyframe count.
  void replace_map(const std::vector<MapKeyframe>& keyframes, const Eigen::Isometry3d& correction,
                   double yaw);

  // The map's keyframes from `first` on, each moved by `moved` (points, normals, position), as
  // replace_map takes them.
  std::vector<MapKeyframe> moved_keyframes(const Eigen::Isometry3d& moved,
                                           std::size_t first = 0) const;

  // False while the map's heading may still be turned onto the source's (icp.heading_anchor):
  // whoever keeps copies of keyframes in the map's frame turns them by the report's frame_turn.
  bool frame_settled() const { return heading_anchor_.settled(); }

  const WorldMap& map() const { return map_; }
  const Pose& pose() const { return pose_; }
  const SlamConfig& config() const { return config_; }
  // rad/s: how fast the orientation source's heading drifts, as the checks have learnt it
  // (extensions/HeadingRate); the correction turns back by as much. 0 while none is shown.
  double heading_drift() const {
    return config_.icp.heading == HeadingMode::PeriodicCheck ? -heading_rate_.rate() : 0.0;
  }
  // Each keyframe's first point in the map, in keyframe order (a keyframe that added nothing
  // shares its start with the next).
  const std::vector<std::size_t>& keyframe_starts() const {
    return map_uncertainty_.first_points();
  }
  // Beyond the seed: for each keyframe, how far its heading is from where the drift learnt since
  // puts it (extensions/HeadingRate::turns); none while the drift learnt leaves every keyframe
  // within icp.heading_check_tolerance. Applied by whoever can move the keyframes (the back end).
  std::optional<std::vector<double>> heading_turns() const;
  // Each keyframe's scan stamp, in keyframe order.
  const std::vector<double>& keyframe_stamps() const { return keyframe_stamps_; }
  // rad about the vertical: what the matcher has added to the orientation source's heading so
  // far (always 0 with icp.heading: source, the seed).
  double heading_correction() const { return heading_correction_; }
  // How many scans ended in each outcome, indexed by ScanOutcome.
  const std::array<std::size_t, kScanOutcomeCount>& outcome_counts() const { return counts_; }
  std::size_t rejected_imu_samples() const { return imu_.rejected(); }

 private:
  ScanReport finish(ScanReport report);
  Eigen::Quaterniond corrected(const Eigen::Quaterniond& source_orientation) const;
  bool heading_check_due(const Pose& predicted) const;
  MatchResult match(const ScanPoints& points, const Pose& predicted);
  bool yaw_blind(MatchResult& match) const;
  bool heading_seen(const Eigen::Quaterniond& orientation) const;
  bool stale(double stamp) const;
  bool moved_enough_for_map_update(const Pose& pose) const;
  // wall_normals: the scan's (wall_normals), for the beams a blind keyframe keeps whole.
  void add_to_map(ScanReport& report, const ProjectedScan& projected,
                  const std::vector<Vec3>& wall_normals);
  SweepMotion sweep_motion(const Scan& scan, const Vec3& predicted) const;
  ProjectedScan project(const Scan& scan, const Eigen::Quaterniond& orientation,
                        ScanReport& report) const;
  // `returns`: the scan's level points, world-oriented about the body (as ProjectedScan's).
  void remember_free_space(const Scan& scan, Points returns);
  ScanPoints scan_points(const ProjectedScan& projected, const std::vector<Vec3>& normals) const;
  MapError map_part(const ScanReport& report, const MatchResult& match) const;
  struct KeyframeError {
    CorrelatedError inherited;  // the map's, where the scan matched
    Eigen::Matrix4d own;        // the match's own noise's covariance
  };
  KeyframeError keyframe_error(const ScanReport& report) const;
  Eigen::Vector2d heading_drift_terms() const;
  std::pair<Eigen::Vector4d, Eigen::Vector4d> keyframe_drift() const;
  Eigen::Matrix4d map_total() const;
  Eigen::Matrix3d map_covariance(const Eigen::Matrix3d& covariance) const;
  void follow_heading_drift(double stamp);
  void anchor_heading(ScanReport& report);
  void height_from_floor(ScanReport& report, const ProjectedScan& projected);
  void rebuild_map(const std::vector<MapKeyframe>& keyframes);
  void move_with_map(const Eigen::Isometry3d& moved, double yaw);
  // What a check before a keyframe says of the source's drift (HeadingRate::add_check's terms).
  struct DriftCheck {
    double disagreement = 0.0;
    double span = 0.0;
    double applied = 0.0;
  };
  std::optional<DriftCheck> drift_check(const MatchResult& check, double stamp) const;
  Eigen::Matrix3d predicted_covariance(const MotionPrediction& prediction, double stamp) const;
  // `prior`: predicted_covariance at the scan, computed once per scan for these.
  ScanReport carried_by_prior(ScanReport& report, const Pose& start, const Eigen::Matrix3d& prior,
                              bool has_prior);
  std::optional<PriorDistance> distance_from_prior(const ScanReport& report, const Vec3& measured,
                                                   const Pose& start,
                                                   const MotionPrediction& prediction,
                                                   const Eigen::Matrix3d& prior) const;
  bool yaw_estimated(const MatchResult& match) const;
  // Every beam of the scan, unthinned, with its wall normal (empty without the analysis).
  struct EveryBeam {
    const ProjectedScan& projected;
    const std::vector<Vec3>& normals;
  };
  std::vector<Vec3> wall_normals(const ProjectedScan& projected) const;
  std::vector<std::size_t> facing_weakest(const std::vector<Vec3>& normals) const;
  Vec3 keep_what_the_scan_saw(ScanReport& report, const MatchResult& match, const EveryBeam& beams,
                              const Pose& start, const Eigen::Matrix3d& prior,
                              const ScanGeometry& sensor, Vec3& measured);
  std::optional<double> search_blind_direction(ScanReport& report, const MatchResult& match,
                                               const EveryBeam& beams, const Pose& start,
                                               const Eigen::Matrix3d& prior, double sigma);
  MapPointFilter placed_better_than(const Vec3& e, double prior_variance) const;

  SlamConfig config_;
  ImuBuffer imu_;
  WorldMap map_;
  ScanMatcher matcher_;
  Pose pose_;
  Vec3 last_map_update_position_ = Vec3::Zero();
  double last_map_update_heading_ = 0.0;
  double heading_correction_ = 0.0;
  int scans_since_heading_check_ = 0;
  std::array<std::size_t, kScanOutcomeCount> counts_{};
  std::vector<Neighbour> nearest_;  // the last match's neighbours, the next one's warm start
  Eigen::Matrix3d covariance_ = Eigen::Matrix3d::Zero();  // of pose_.position
  MatchNoise match_noise_;
  PriorGate gate_;
  MapUncertainty map_uncertainty_;
  std::size_t blind_stretches_ = 0;  // blind stretches begun (CorrelatedError::carried)
  bool in_blind_stretch_ = false;
  MapError map_error_;  // the last match's, (x, y, z, yaw)
  HeadingRate heading_rate_;
  HeadingAnchor heading_anchor_;
  FloorLevel floor_level_;
  FreeSpace free_space_;  // what the accepted scans' beams saw through (free_space.enabled)
  std::optional<double> drift_followed_until_;  // the stamp the drift was added up to
  std::optional<DriftCheck> drift_check_;       // this scan's, until the gate has judged it
  std::vector<double> keyframe_stamps_;         // one per keyframe, with
  std::vector<double> keyframe_headings_;       // the heading correction then
};

}  // namespace uavslam
