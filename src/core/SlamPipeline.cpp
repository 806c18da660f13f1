#include "core/SlamPipeline.hpp"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/Angles.hpp"
#include "core/Heading.hpp"
#include "core/extensions/BlindDirectionSearch.hpp"
#include "core/extensions/FloorReturns.hpp"
#include "core/extensions/PriorAgreement.hpp"
#include "core/extensions/Relocalisation.hpp"
#include "core/extensions/ScanInformation.hpp"
#include "core/extensions/SurfaceNormals.hpp"

namespace uavslam {
namespace {

// A translation in three unknowns needs at least this many pairs to be more than a guess.
constexpr std::size_t kMinPoints = 10;

bool is_well_formed(const Scan& scan) {
  return scan.geometry && std::isfinite(scan.stamp) &&
         scan.ranges.size() == scan.geometry->directions.size() && !scan.ranges.empty();
}

double angle_between(double a, double b) {
  return std::abs(wrap_angle(a - b));
}

// Every level beam with a wall normal (a jamb's few beams are too few thinned), turned and placed
// as the match put the scan across e, and at the start along it:
//   q = p_match + R(yaw) p + e e.(p_start - p_match)
ScanPoints level_beams_at_start(const ProjectedScan& projected, const std::vector<Vec3>& normals,
                                const MatchResult& match, const Vec3& start, const Vec3& e) {
  const Eigen::Matrix3d turn = yaw_rotation(match.yaw).toRotationMatrix();
  const Vec3 origin = match.position + e * e.dot(start - match.position);
  ScanPoints level;
  for (std::size_t i = 0; i < projected.points.size() && i < normals.size(); ++i) {
    if (projected.vertical[i] || normals[i].isZero()) continue;
    level.points.push_back(origin + turn * projected.points[i]);
    level.weights.emplace_back(1.0, 1.0, 0.0);
    level.normals.push_back(turn * normals[i]);
  }
  return level;
}

}  // namespace

SlamPipeline::SlamPipeline(const SlamConfig& config, const Vec3& initial_position)
    : config_(config),
      imu_(config.imu.max_gap),
      map_(make_nearest_neighbour_index(config.nearest_neighbour), config.map.min_point_spacing),
      matcher_(config.icp),
      gate_(config.icp.prior_gate, config.icp.prior_gate_overrule),
      heading_rate_(config.imu.heading_drift_sigma),
      heading_anchor_(config.icp.heading == HeadingMode::EveryScan ? config.icp.heading_anchor
                                                                   : 0.0),
      floor_level_(config.floor.level_window, config.floor.level_gate, config.floor.flatness),
      free_space_(config.free_space.resolution, config.free_space.reach,
                  config.free_space.min_passes, config.free_space.memory,
                  std::max(config.icp.max_correspondence_distance, config.free_space.resolution)) {
  pose_.position = initial_position;
}

void SlamPipeline::add_imu(const ImuSample& sample) {
  imu_.add(sample);
}

ScanReport SlamPipeline::process_scan(const Scan& scan, const MotionPrediction& prediction) {
  ScanReport report;
  report.pose = pose_;
  if (!is_well_formed(scan)) return finish(report);

  // Step 1: orientation at the scan's time, points into the world orientation.
  const auto source_orientation = imu_.orientation_at(scan.stamp);
  if (!source_orientation) {
    report.outcome = ScanOutcome::NoImu;
    return finish(report);
  }
  follow_heading_drift(scan.stamp);
  drift_check_.reset();
  Eigen::Quaterniond orientation = corrected(*source_orientation);
  // The motion prior's motion since the last pose, in the map's frame (turned by the heading
  // correction, if any).
  const Vec3 predicted = heading_correction_ == 0.0
                             ? prediction.motion
                             : yaw_rotation(heading_correction_) * prediction.motion;
  report.sweep = sweep_motion(scan, predicted);
  ProjectedScan projected = project(scan, orientation, report);
  // Step 2: every k-th point.
  std::vector<Vec3> normals = wall_normals(projected);
  ScanPoints points = scan_points(projected, normals);
  report.points_used = points.points.size();
  if (report.points_used < kMinPoints) {
    report.outcome = ScanOutcome::TooFewPoints;
    return finish(report);
  }

  if (map_.empty()) {
    // The first scan seeds the map where the vehicle starts.
    pose_ = {scan.stamp, pose_.position, orientation};
    report.outcome = ScanOutcome::MapInitialised;
    height_from_floor(report, projected);
    report.pose = pose_;
    add_to_map(report, projected, normals);
    remember_free_space(scan, level_points(projected));
    anchor_heading(report);
    return finish(report);
  }

  // Steps 3-5: the ICP from the last position (the seed) moved by the prediction. The matcher
  // measures its correction, and so the seed's 1 m "distance moved" check, from this start: the
  // check limits what the matcher changed, not the predicted motion itself.
  const Pose start{scan.stamp, pose_.position + predicted, orientation};
  const Eigen::Matrix3d prior = predicted_covariance(prediction, start.stamp);
  report.relocalised = stale(scan.stamp);
  MatchResult match =
      report.relocalised
          ? relocalise(matcher_, map_, points,
                       search_starts(start.position,
                                     search_radius(config_.recovery, scan.stamp - pose_.stamp),
                                     config_.recovery.grid_step),
                       config_.icp.heading == HeadingMode::EveryScan)
          : this->match(points, start);
  // Beyond the seed: what the scan saw where the beams had seen empty space moved there; matched
  // again without it (free_space.enabled). Judged at the match's pose, not the prediction's: a
  // start a few decimetres off would put the walls themselves into the free space in front of them.
  // Every return still goes into the free space: a wall taken for moved (a turn's first views
  // placed a little off) is a surface again after a few scans.
  Points returns = config_.free_space.enabled ? level_points(projected) : Points{};
  if (config_.free_space.enabled && !report.relocalised && match.outcome == ScanOutcome::Accepted) {
    report.moving_points = set_aside_moving(projected, match.position, match.yaw, free_space_);
    if (report.moving_points > 0) {
      normals = wall_normals(projected);
      points = scan_points(projected, normals);
      match = this->match(points, start);
    }
  }
  report.outcome = match.outcome;
  report.error_before = match.error_before;
  report.error_after = match.error_after;
  report.iterations = match.iterations;
  report.yaw_held = match.yaw_held;
  if (match.outcome != ScanOutcome::Accepted) {
    return carried_by_prior(report, start, prior, prediction.covariance.has_value());
  }

  // Beyond the seed: what the scan saw, and whether the match agrees with the motion prior there.
  Vec3 measured = match.position;
  const Vec3 position = keep_what_the_scan_saw(report, match, {projected, normals}, start, prior,
                                               *scan.geometry, measured);
  const std::optional<PriorDistance> distance =
      distance_from_prior(report, measured, start, prediction, prior);
  if (distance && !report.relocalised) {
    report.prior_distance = distance->sigmas;
    const Vec3 correction = measured - start.position;
    // The gate measures in the learnt scales: none until they have settled.
    const PriorGate::Verdict verdict =
        match_noise_.settled() ? gate_.judge(*distance, correction, report.seen.observed,
                                             match_noise_.scaled(report.seen.covariance))
                               : PriorGate::Verdict::Agrees;
    // Learnt from every match, the gated ones too: a gate that kept its refusals out of the scale
    // it is measured in would learn too small a scale and refuse ever more.
    match_noise_.add(correction, report.seen.observed, report.seen.covariance, prior);
    if (verdict == PriorGate::Verdict::Rejected) {
      report.outcome = ScanOutcome::DisagreesWithPrior;
      return carried_by_prior(report, start, prior, true);
    }
    report.prior_overruled = verdict == PriorGate::Verdict::Overrules;
  }

  // A scan the gate let through: its check, if it made one before a keyframe, says how the
  // source drifts (one the gate refused, a late scan's, says nothing).
  if (drift_check_) {
    heading_rate_.add_check(drift_check_->disagreement, drift_check_->span, drift_check_->applied);
  }

  // The heading the scan agreed with becomes the correction for this and later scans.
  if (match.yaw != 0.0) {
    heading_correction_ = wrap_angle(heading_correction_ + match.yaw);
    orientation = corrected(*source_orientation);
    projected = project(scan, orientation, report);
    if (config_.free_space.enabled) {
      returns = level_points(projected);
      set_aside_moving(projected, position, 0.0, free_space_);
    }
  }

  // Steps 6-7: report the new pose; a keyframe after enough motion.
  pose_ = {scan.stamp, position, orientation};
  covariance_ = report.covariance;
  if (config_.degeneracy.threshold > 0.0) map_error_ = map_part(report, match);
  height_from_floor(report, projected);
  report.map_covariance = map_covariance(report.covariance);
  report.pose = pose_;
  if (moved_enough_for_map_update(pose_)) add_to_map(report, projected, normals);
  remember_free_space(scan, returns);
  anchor_heading(report);
  return finish(report);
}

// Beyond the seed (extensions/HeadingAnchor): once the first scans have measured how far the
// map's heading is from the source's, the map, its keyframes and the pose turn onto it about the
// take-off point, and the heading correction with them.
void SlamPipeline::anchor_heading(ScanReport& report) {
  const std::optional<double> yaw = heading_anchor_.add(report.pose.stamp, heading_correction_);
  if (!yaw || *yaw == 0.0) return;
  const FrameTurn turn{map_uncertainty_.positions().front(), *yaw};
  const Eigen::Isometry3d moved = turn.transform();
  rebuild_map(moved_keyframes(moved));
  for (double& heading : keyframe_headings_) heading = wrap_angle(heading + *yaw);
  move_with_map(moved, *yaw);
  for (Vec3& p : report.added_points) p = moved * p;
  report.sweep.velocity = yaw_rotation(*yaw) * report.sweep.velocity;
  report.pose = pose_;
  report.frame_turn = turn;
}

// Beyond the seed (extensions/FloorLevel): where the floor seen is the floor taken off from, its
// level measures the height absolutely, and the match's height, chained through the map, is fused
// with it by their variances (the match's and the map's under it, the whole of what the chained
// height may be off by):
//   z = (z_m / v_m + z_f / v_f) / (1 / v_m + 1 / v_f),   v = 1 / (1 / v_m + 1 / v_f)
// The height is then absolute: the map's part of its covariance no longer stands under it.
void SlamPipeline::height_from_floor(ScanReport& report, const ProjectedScan& projected) {
  if (config_.floor.level_gate <= 0.0) return;
  const std::optional<FloorSighting> floor = floor_below(projected);
  if (!floor) return;
  const std::optional<HeightFix> fix = floor_level_.add(pose_.stamp, pose_.position.z(), *floor);
  if (!fix) return;
  // Without a covariance (degeneracy off) the match's height states no spread: the fix's stands.
  HeightFix fused = *fix;
  const double chained = covariance_(2, 2) + map_error_.covariance()(2, 2);
  if (chained > 0.0) {
    fused.variance = 1.0 / (1.0 / chained + 1.0 / fix->variance);
    fused.height = fused.variance * (pose_.position.z() / chained + fix->height / fix->variance);
  }
  pose_.position.z() = fused.height;
  covariance_.row(2).setZero();
  covariance_.col(2).setZero();
  covariance_(2, 2) = fused.variance;
  map_error_.error.forget(2);
  map_error_.drift(2) = 0.0;
  map_error_.applied(2) = 0.0;
  report.covariance = covariance_;
  report.height_from_floor = true;
}

// A rejected scan: with a motion prior, the vehicle went where the prior says (the start, also
// when that is where it was: wheels that stood still), with the prior's covariance; without one
// (the seed), the pose stays and the scan gets none.
ScanReport SlamPipeline::carried_by_prior(ScanReport& report, const Pose& start,
                                          const Eigen::Matrix3d& prior, bool has_prior) {
  if (!has_prior && start.position == pose_.position) return finish(report);
  covariance_ = prior;
  pose_ = start;
  report.pose = pose_;
  report.covariance = covariance_;
  report.map_covariance = map_covariance(report.covariance);
  report.dead_reckoned = true;
  return finish(report);
}

// The match's correction of the prediction, in the directions the scan fixed, in standard
// deviations of the two together (extensions/PriorAgreement): the match's covariance as
// MatchNoise has learnt to scale it, the prior's own (`prior`). None without the degeneracy
// analysis (no match covariance) or a prior with a covariance.
std::optional<PriorDistance> SlamPipeline::distance_from_prior(const ScanReport& report,
                                                               const Vec3& measured,
                                                               const Pose& start,
                                                               const MotionPrediction& prediction,
                                                               const Eigen::Matrix3d& prior) const {
  if (!prediction.covariance || config_.degeneracy.threshold <= 0.0) return std::nullopt;
  return uavslam::distance_from_prior(measured - start.position, report.seen.observed,
                                      match_noise_.scaled(report.seen.covariance) + prior);
}

// The seed trusts the source (heading: source); otherwise the heading is estimated in every scan
// or checked every heading_check_every scans and before every keyframe (a scan that joins the
// map with the source's heading error would turn the map itself). A check that finds the heading
// within tolerance leaves it alone and takes the seed's translation-only result.
MatchResult SlamPipeline::match(const ScanPoints& points, const Pose& predicted) {
  const HeadingMode heading = config_.icp.heading;
  const Vec3& start = predicted.position;
  if (heading == HeadingMode::EveryScan) {
    MatchResult turned =
        matcher_.match(map_, points, start, heading_seen(predicted.orientation), &nearest_);
    if (turned.outcome != ScanOutcome::Accepted || !yaw_blind(turned)) return turned;
    MatchResult held = matcher_.match(map_, points, start, false, &nearest_);
    if (held.outcome != ScanOutcome::Accepted) return turned;
    held.yaw_held = true;
    return held;
  }
  if (heading == HeadingMode::PeriodicCheck && heading_check_due(predicted)) {
    scans_since_heading_check_ = 0;
    MatchResult checked = matcher_.match(map_, points, start, true, &nearest_);
    if (checked.outcome == ScanOutcome::Accepted) {
      // The drift from the checks before keyframes only: those between two keyframes see the
      // same map from nearly the same place and share its noise, which a rate learnt from all of
      // them took for a drift (demo.yaml, seed 2: 1 degree a minute for 15 s).
      if (moved_enough_for_map_update(predicted)) {
        drift_check_ = drift_check(checked, predicted.stamp);
      }
      if (std::abs(checked.yaw) > config_.icp.heading_check_tolerance) return checked;
    }
  }
  ++scans_since_heading_check_;
  return matcher_.match(map_, points, start, false, &nearest_);
}

// A scanner tilted beyond icp.heading_max_tilt cuts the room at another slant than the map's level
// keyframes did: over a shelf and onto the wall behind it, under a table, onto a ceiling. Its
// points still place the vehicle, but the turn they ask for follows those differences (the
// agile flight's take-off, tilting to 15 degrees: the heading walked by a degree in a second); the
// heading stays the source's (with the correction so far) until the vehicle levels again.
bool SlamPipeline::heading_seen(const Eigen::Quaterniond& orientation) const {
  const double max_tilt = config_.icp.heading_max_tilt;
  return max_tilt <= 0.0 || tilt_of(orientation) <= max_tilt;
}

// Beyond the seed (scan.deskew): how the body moved while the scanner swept, from the IMU's rate
// at mid-sweep and the prior's mean velocity since the last pose (over 25 ms at 40 Hz, the
// velocity changes by far less than the motion itself). None without fire times.
SweepMotion SlamPipeline::sweep_motion(const Scan& scan, const Vec3& predicted) const {
  const std::vector<double>& fire_times = scan.geometry->fire_times;
  if (!config_.scan.deskew || fire_times.empty()) return {};
  SweepMotion sweep;
  const double middle = scan.stamp + 0.5 * fire_times.back();
  if (const std::optional<Vec3> rate = imu_.angular_velocity_at(middle)) {
    sweep.angular_velocity = *rate;
  }
  // A motion over less time than the sweep takes says more of the stamps' jitter than of the
  // velocity (a log's scans 1 ms apart): then the turn alone.
  const double since_pose = scan.stamp - pose_.stamp;
  if (!map_.empty() && since_pose >= scan.geometry->sweep_seconds() && since_pose > 0.0) {
    sweep.velocity = predicted / since_pose;
  }
  return sweep;
}

// Step 1's points; beyond the seed, without the floor strikes of a tilted scanner's level beams,
// each beam from where the body was when it fired.
ProjectedScan SlamPipeline::project(const Scan& scan, const Eigen::Quaterniond& orientation,
                                    ScanReport& report) const {
  ProjectedScan projected = project_scan(scan, orientation, report.sweep);
  report.invalid_ranges = projected.invalid;
  if (config_.scan.floor_margin > 0.0) {
    report.floor_returns = set_aside_floor_returns(projected, config_.scan.floor_margin);
  }
  return projected;
}

// Beyond the seed: the beams of a scan placed at the pose into what the scans have seen through
// (extensions/FreeSpace), from the scanner's position.
void SlamPipeline::remember_free_space(const Scan& scan, Points returns) {
  if (!config_.free_space.enabled) return;
  const Vec3 sensor = pose_.position + pose_.orientation * scan.geometry->mount.translation();
  apply_transform(returns, pose_.position);
  free_space_.add_scan(pose_.stamp, sensor, returns);
}

// Every beam's wall normal when the degeneracy analysis needs them (none otherwise): every
// neighbour within the gap (0.2 m), up to 20 beams away. A line fitted over a few centimetres of a
// near wall is noise (0.25 degree beams lie 4 mm apart at 1 m; ranges err by about 1 cm), and noise
// in the normals reads as information along the wall.
std::vector<Vec3> SlamPipeline::wall_normals(const ProjectedScan& projected) const {
  if (config_.degeneracy.threshold <= 0.0) return {};
  SurfaceNormalOptions wide;
  wide.half_window = 20;
  return estimate_normals(projected.points, projected.vertical, wide);
}

// Steps 1-2's points, thinned to every k-th, with each point's wall normal where known.
ScanPoints SlamPipeline::scan_points(const ProjectedScan& projected,
                                     const std::vector<Vec3>& normals) const {
  const int k = config_.scan.subsample_every;
  ScanPoints points = weigh_points(keep_every_kth(projected.points, k),
                                   keep_every_kth(projected.vertical, k), config_.icp.split_axes);
  if (!normals.empty()) points.normals = keep_every_kth(normals, k);
  return points;
}

// Beyond the seed: a turn and a shift together leave the scan nearly unchanged (a round room seen
// off its centre), so the yaw it found is where the ICP slid to (degeneracy.threshold, on the
// yaw's information fraction, ScanInformation).
bool SlamPipeline::yaw_blind(MatchResult& match) const {
  const SlamConfig::Degeneracy& options = config_.degeneracy;
  if (!options.hold_blind_yaw || options.threshold <= 0.0 || match.yaw == 0.0) return false;
  match.information = scan_information(match.pairs, match.position, true, options.min_sigma);
  return match.information->horizontal_pairs > 0 &&
         match.information->yaw_fraction < options.threshold;
}

// The match turned the scan as well as moving it: heading estimated in every scan, or a check
// that found the heading off.
bool SlamPipeline::yaw_estimated(const MatchResult& match) const {
  return config_.icp.heading == HeadingMode::EveryScan || match.yaw != 0.0;
}

// Beyond the seed: where the scan is blind (a corridor's axis), the match only held the start, so
// the position along those directions stays as the motion prior predicted it:
//   p = p_start + P (p_match - p_start)   (P: projection onto the directions the scan fixes)
// and the covariance is the match's there (as MatchNoise has learnt to scale it), the
// prediction's elsewhere:
//   Sigma = Sigma_scan + (I - P) Sigma_predicted (I - P)
// With no predicted covariance (no motion model), the vehicle may have gone recovery.max_speed
// per second along a blind direction since the last pose.
// Height counts only for a sensor with floor beams, and with the per-axis weights that give them
// to z (icp.split_axes): a planar scanner's z is not the scan's to see, nor degenerate.
// A blind direction a structure across it fixes (search_blind_direction) counts as fixed, at the
// search's offset; `measured` is then the match with that offset along it (what the gate and
// MatchNoise measure), else the match itself.
Vec3 SlamPipeline::keep_what_the_scan_saw(ScanReport& report, const MatchResult& match,
                                          const EveryBeam& beams, const Pose& start,
                                          const Eigen::Matrix3d& prior, const ScanGeometry& sensor,
                                          Vec3& measured) {
  if (config_.degeneracy.threshold <= 0.0) return match.position;
  const bool measures_height = config_.icp.split_axes && sensor.has_vertical_beams();
  const ScanInformation information =
      match.information ? *match.information
                        : scan_information(match.pairs, match.position, yaw_estimated(match),
                                           config_.degeneracy.min_sigma);
  report.seen = observability(information, config_.degeneracy.threshold, measures_height);
  Vec3 position = start.position + report.seen.observed * (match.position - start.position);
  if (const std::optional<double> along =
          search_blind_direction(report, match, beams, start, prior, information.sigma)) {
    // What the scan measured along e is the fix, not where the ICP slid.
    const Vec3& e = report.seen.weakest;
    position += *along * e;
    measured += e * (*along - e.dot(match.position - start.position));
  }
  const Eigen::Matrix3d blind = Eigen::Matrix3d::Identity() - report.seen.observed;
  report.covariance =
      match_noise_.scaled(report.seen.covariance) + blind * prior * blind.transpose();
  // A scan that sees every direction ends a blind stretch; the next blind one starts another.
  if (report.seen.degenerate == 0) {
    in_blind_stretch_ = false;
  } else if (!in_blind_stretch_) {
    in_blind_stretch_ = true;
    ++blind_stretches_;
  }
  return position;
}

// Beyond the seed (extensions/BlindDirectionSearch): the horizontal direction the scan left blind
// (the other one seen) searched for a structure that fixes it, over the prior's 3 sigma along it
// (at most degeneracy.search_window). Found: the direction counts as seen, with the fix's
// variance sigma^2 / sum_i (n_i . e)^2, and the offset from the start along it is returned.
std::optional<double> SlamPipeline::search_blind_direction(
    ScanReport& report, const MatchResult& match, const EveryBeam& beams, const Pose& start,
    const Eigen::Matrix3d& prior, double sigma) {
  const SlamConfig::Degeneracy& options = config_.degeneracy;
  Observability& seen = report.seen;
  const Vec3& e = seen.weakest;
  const bool one_blind =
      seen.observed.topLeftCorner<2, 2>().trace() > 0.5 && (seen.observed * e).norm() < 0.5;
  if (options.search_window <= 0.0 || !one_blind) return std::nullopt;
  const double prior_variance = std::max(e.dot(prior * e), 0.0);
  BlindSearchOptions search;
  search.half_width = std::min(options.search_window, 3.0 * std::sqrt(prior_variance));
  if (search.half_width < 2.0 * options.search_step) return std::nullopt;  // the prior knows it
  search.step = options.search_step;
  search.cap = 3.0 * sigma;
  search.max_distance = config_.icp.max_correspondence_distance;
  search.uniqueness = options.search_uniqueness;
  const std::optional<DirectionFix> fix = uavslam::search_blind_direction(
      map_, level_beams_at_start(beams.projected, beams.normals, match, start.position, e), e,
      search, placed_better_than(e, prior_variance));
  if (!fix) return std::nullopt;
  report.blind_fixed = true;
  seen.observed += e * e.transpose();
  // The scan's noise averages over its pairs, the map's only over the few map points they took
  // (a far jamb's handful): sigma^2 (1 / sum J^2 + 1 / map points), and at least
  // search_sigma^2: such fixes at take-off err by 1-2 cm where that says 3-5 mm (corridor.yaml).
  const double variance =
      std::max(sigma * sigma * (1.0 / fix->information + 1.0 / double(fix->map_points)),
               options.search_sigma * options.search_sigma);
  seen.covariance += e * e.transpose() * variance;
  --seen.degenerate;
  return fix->offset;
}

// The map points of keyframes placed along e at least twice as well as the prior places the
// vehicle (variance a quarter of prior_variance): a keyframe made blind along e carries the drift
// a search is to end, and its copy of a door jamb would only confirm it.
MapPointFilter SlamPipeline::placed_better_than(const Vec3& e, double prior_variance) const {
  std::vector<bool> placed;
  for (std::size_t k = 0; k < map_uncertainty_.keyframes(); ++k) {
    const Eigen::Matrix3d own = map_uncertainty_.keyframe_covariance(k).topLeftCorner<3, 3>();
    placed.push_back(e.dot(own * e) <= 0.25 * prior_variance);
  }
  return [this, placed = std::move(placed)](std::size_t index) {
    const std::optional<std::size_t> k = map_uncertainty_.keyframe_of(index);
    return k && placed[*k];
  };
}

// How well the map the scan matched is placed (extensions/MapUncertainty), over (x, y, z, yaw),
// in the directions the scan fixed. A blind direction keeps what it had: there the position is
// the prior's, carried from the last fixes, and the prior's covariance is relative to the map
// those fixes were made against (the inertial filter takes map-relative fixes), so the map's
// error at them still stands under it:
//   e_map = T e_pairs + B e_map,last,   T = diag(P, 1), B = diag(I - P, 0)
// and the drift's terms likewise: a = T a_pairs + B a_last, h = T h_pairs + B h_last.
MapError SlamPipeline::map_part(const ScanReport& report, const MatchResult& match) const {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = report.seen.observed;
  Eigen::Matrix4d B = Eigen::Matrix4d::Zero();
  B.topLeftCorner<3, 3>() = Eigen::Matrix3d::Identity() - report.seen.observed;
  const MapError pairs = map_uncertainty_.of_match(match.pairs, match.position,
                                                   heading_drift_terms(), yaw_estimated(match));
  MapError error;
  error.error.add(T, pairs.error);
  error.error.add(B, map_error_.error);
  error.error.prune(MapUncertainty::kSourcesKept);
  error.drift = T * pairs.drift + B * map_error_.drift;
  error.applied = T * pairs.applied + B * map_error_.applied;
  return error;
}

// What a keyframe joins the map with, over (x, y, z, yaw): the map's error where the scan matched
// (inherited, shared with the keyframes it came from) and the match's own noise. The heading's:
// taken from the source as it is (the seed), the source's, imu.heading_sigma, and not the map's;
// estimated in every scan, the map's plus the match's own (the yaw's variance with the translation
// estimated beside it, scaled as MatchNoise scales the match's: without it each keyframe's heading
// was as sure as the map's, and a flight's NEES averaged 9.7 on the demo); checked against the map
// (icp.heading: periodic_check), the map's, the source's drift not followed, which
// keyframe_drift() carries apart.
SlamPipeline::KeyframeError SlamPipeline::keyframe_error(const ScanReport& report) const {
  KeyframeError error{map_error_.error, Eigen::Matrix4d::Zero()};
  error.own.topLeftCorner<3, 3>() = report.covariance;
  // Along the directions the scan left blind the position is the motion prior's, whose error the
  // keyframes carried through one blind stretch share (CorrelatedError::carried): as fresh noises,
  // their differences along a corridor's axis turned the matches on them.
  const Eigen::Matrix3d blind = Eigen::Matrix3d::Identity() - report.seen.observed;
  Eigen::Matrix4d carried = Eigen::Matrix4d::Zero();
  carried.topLeftCorner<3, 3>() = blind * report.covariance * blind.transpose();
  if (!carried.isZero()) {
    error.own -= carried;
    error.inherited.add_noise(CorrelatedError::carried(blind_stretches_), carried);
  }
  if (config_.icp.heading == HeadingMode::Source) {
    error.inherited.forget(3);
    error.own(3, 3) = config_.imu.heading_sigma * config_.imu.heading_sigma;
  }
  if (config_.icp.heading == HeadingMode::EveryScan) {
    error.own(3, 3) = match_noise_.horizontal_scale() * report.seen.yaw_variance;
  }
  return error;
}

// The drift terms of the heading the vehicle has now (MapError): the time since the first
// keyframe (a) and the correction applied since (h). The source's heading is absolute but for the
// drift: it is off by r_true dt - h whatever map it was checked against. Checked headings only.
Eigen::Vector2d SlamPipeline::heading_drift_terms() const {
  if (config_.icp.heading != HeadingMode::PeriodicCheck || keyframe_stamps_.empty()) {
    return Eigen::Vector2d::Zero();
  }
  return {pose_.stamp - keyframe_stamps_.front(),
          wrap_angle(heading_correction_ - keyframe_headings_.front())};
}

// A keyframe's drift terms: its heading's as above, its position's the map's where it matched.
std::pair<Eigen::Vector4d, Eigen::Vector4d> SlamPipeline::keyframe_drift() const {
  const Eigen::Vector2d heading = heading_drift_terms();
  Eigen::Vector4d drift = map_error_.drift;
  Eigen::Vector4d applied = map_error_.applied;
  drift(3) = heading(0);
  applied(3) = heading(1);
  return {drift, applied};
}

// The map's covariance where the scan matched, the drift's part weighed with the rate as the
// checks know it now (checked headings only). Where the map's heading is anchored on the
// source's (HeadingAnchor), plus how far it may be turned from it about the take-off point o: a
// turn eps moves the vehicle by eps perp(p - o), so
//   Sigma += var(eps) a a^T,   a = (perp(p - o), 1)
// over (x, y, z, yaw): a far match a lever arm's share, the heading the whole of it.
Eigen::Matrix4d SlamPipeline::map_total() const {
  Eigen::Matrix4d total = map_error_.total(0.0, 0.0);
  if (config_.icp.heading == HeadingMode::PeriodicCheck) {
    const HeadingRate::Estimate rate = heading_rate_.estimate();
    total = map_error_.total(rate.rate, rate.variance);
  }
  const double frame = heading_anchor_.variance();
  if (frame > 0.0 && map_uncertainty_.keyframes() > 0) {
    const Vec3 arm = pose_.position - map_uncertainty_.positions().front();
    const Eigen::Vector4d a(-arm.y(), arm.x(), 0.0, 1.0);
    total += frame * a * a.transpose();
  }
  return total;
}

// The map's part of the pose's covariance (map_total), given the pose's own relative to the map
// (`covariance`): an error e from the map, turned by the map's heading error psi, moves by
// psi perp(e) (first order), so
//   Sigma_map += var(psi) J Sigma_xy J^T,   J = [0 -1; 1 0]
// Where the scan saw, e is millimetres and this nothing; along a corridor's blind axis the prior
// spreads metres, and the map's heading error turns their share across it (plain_corridor with
// an accelerometer's bias, lost along the axis: a NEES of 310 without it).
Eigen::Matrix3d SlamPipeline::map_covariance(const Eigen::Matrix3d& covariance) const {
  const Eigen::Matrix4d total = map_total();
  Eigen::Matrix3d map = total.topLeftCorner<3, 3>();
  Eigen::Matrix2d J;
  J << 0.0, -1.0, 1.0, 0.0;
  map.topLeftCorner<2, 2>() +=
      std::max(total(3, 3), 0.0) * J * covariance.topLeftCorner<2, 2>() * J.transpose();
  return map;
}

// Beyond the seed: the source's heading drift as the checks have learnt it (extensions/
// HeadingRate), added to the correction since the last scan.
void SlamPipeline::follow_heading_drift(double stamp) {
  if (config_.icp.heading == HeadingMode::PeriodicCheck && drift_followed_until_ &&
      stamp > *drift_followed_until_) {
    heading_correction_ =
        wrap_angle(heading_correction_ + heading_rate_.rate() * (stamp - *drift_followed_until_));
  }
  drift_followed_until_ = stamp;
}

std::optional<std::vector<double>> SlamPipeline::heading_turns() const {
  if (config_.icp.heading != HeadingMode::PeriodicCheck) return std::nullopt;
  std::vector<double> turns = heading_rate_.turns(keyframe_stamps_, keyframe_headings_);
  for (const double turn : turns) {
    if (std::abs(turn) > config_.icp.heading_check_tolerance) return turns;
  }
  return std::nullopt;
}

// A check's disagreement against the map its pairs hold, made on average at t_map with the
// correction H(t_map) then (each keyframe weighted by its share of the heading).
std::optional<SlamPipeline::DriftCheck> SlamPipeline::drift_check(const MatchResult& check,
                                                                  double stamp) const {
  double weight = 0.0;
  double made = 0.0;
  double applied = 0.0;
  for (const auto& [k, share] : map_uncertainty_.heading_shares(check.pairs)) {
    weight += share;
    made += share * keyframe_stamps_[k];
    applied += share * wrap_angle(heading_correction_ - keyframe_headings_[k]);
  }
  if (weight <= 0.0) return std::nullopt;
  return DriftCheck{check.yaw, stamp - made / weight, applied / weight};
}

// The covariance of the predicted position: the prior's own, turned into the corrected heading;
// with no motion model, the last pose's grown by recovery.max_speed per second since it.
Eigen::Matrix3d SlamPipeline::predicted_covariance(const MotionPrediction& prediction,
                                                   double stamp) const {
  if (prediction.covariance) {
    const Eigen::Matrix3d R = yaw_rotation(heading_correction_).toRotationMatrix();
    return R * *prediction.covariance * R.transpose();
  }
  const double reach = config_.recovery.max_speed * (stamp - pose_.stamp);
  return covariance_ + reach * reach * Eigen::Matrix3d::Identity();
}

// A gap in the scans longer than recovery.gap since the last pose: the vehicle may be far from it.
bool SlamPipeline::stale(double stamp) const {
  return config_.recovery.gap > 0.0 && stamp - pose_.stamp > config_.recovery.gap;
}

bool SlamPipeline::heading_check_due(const Pose& predicted) const {
  return scans_since_heading_check_ + 1 >= config_.icp.heading_check_every ||
         moved_enough_for_map_update(predicted);
}

Eigen::Quaterniond SlamPipeline::corrected(const Eigen::Quaterniond& source_orientation) const {
  if (heading_correction_ == 0.0) return source_orientation;
  return yaw_rotation(heading_correction_) * source_orientation;
}

ScanReport SlamPipeline::finish(ScanReport report) {
  ++counts_[static_cast<std::size_t>(report.outcome)];
  report.map_size = map_.size();
  return report;
}

// Seed step 5: "+-0.2 m height and 0.5 m laterally" since the last map update; beyond the seed,
// also a turn of map.keyframe_rotation (when set).
bool SlamPipeline::moved_enough_for_map_update(const Pose& pose) const {
  const Vec3 moved = pose.position - last_map_update_position_;
  const bool turned = config_.map.keyframe_rotation > 0.0 &&
                      angle_between(heading_of(pose.orientation), last_map_update_heading_) >
                          config_.map.keyframe_rotation;
  return std::abs(moved.z()) > config_.map.keyframe_height ||
         moved.head<2>().norm() > config_.map.keyframe_lateral || turned;
}

// Beyond the seed (degeneracy.search_window): the beams that face the direction the scan sees
// least, when it sees it too little (degeneracy.threshold): a door jamb's ten beams, which thinning
// to every k-th leaves two of, too few for a search along a corridor to tell it from noise.
// `normals`: the scan's wall normals (wall_normals); a turn of the scan since turns them all alike,
// and which beams face its weakest direction stays the same.
std::vector<std::size_t> SlamPipeline::facing_weakest(const std::vector<Vec3>& normals) const {
  if (config_.degeneracy.search_window <= 0.0) return {};
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  std::size_t count = 0;
  for (const Vec3& n : normals) {
    if (n.isZero()) continue;
    scatter += n.head<2>() * n.head<2>().transpose();
    ++count;
  }
  if (count == 0) return {};
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(scatter);
  if (solver.eigenvalues()[0] / double(count) >= config_.degeneracy.threshold) return {};
  const Eigen::Vector2d weakest = solver.eigenvectors().col(0);
  const double facing_cosine = BlindSearchOptions{}.facing;  // the search's own choice of beams
  std::vector<std::size_t> facing;
  for (std::size_t i = 0; i < normals.size(); ++i) {
    if (std::abs(normals[i].head<2>().dot(weakest)) >= facing_cosine) facing.push_back(i);
  }
  return facing;
}

// Step 5: the aligned scan, thinned to every k-th point, into the map at the new position; with
// the point-to-line metric, each point's wall normal from its neighbours along the full scan.
void SlamPipeline::add_to_map(ScanReport& report, const ProjectedScan& projected,
                              const std::vector<Vec3>& wall_normals) {
  const int k = config_.map.subsample_every;
  Points aligned = keep_every_kth(projected.points, k);
  std::vector<Vec3> normals;
  if (config_.icp.metric == IcpMetric::PointToLine) {
    const std::vector<Vec3> every = estimate_normals(projected.points, projected.vertical);
    normals = keep_every_kth(every, k);
    for (const std::size_t i : facing_weakest(wall_normals)) {
      if (i % std::size_t(k) == 0) continue;
      aligned.push_back(projected.points[i]);
      normals.push_back(every[i]);
    }
  }
  apply_transform(aligned, pose_.position);
  const auto [drift, applied] = keyframe_drift();
  const KeyframeError error = keyframe_error(report);
  map_uncertainty_.add_keyframe(map_.size(), pose_.position, error.own, drift, applied,
                                error.inherited);
  keyframe_stamps_.push_back(pose_.stamp);
  keyframe_headings_.push_back(heading_correction_);
  report.added_points = map_.add_points(aligned, normals);
  last_map_update_position_ = pose_.position;
  last_map_update_heading_ = heading_of(pose_.orientation);
  report.map_updated = true;
}

void SlamPipeline::replace_map(const std::vector<MapKeyframe>& keyframes,
                               const Eigen::Isometry3d& correction, double yaw) {
  // Checked before the map is replaced (MapUncertainty would refuse them only after).
  if (keyframes.size() != map_uncertainty_.keyframes()) {
    throw std::invalid_argument("replace_map: " + std::to_string(keyframes.size()) +
                                " keyframes for a map of " +
                                std::to_string(map_uncertainty_.keyframes()));
  }
  rebuild_map(keyframes);
  const double drift_rate = heading_rate_.estimate().rate;
  for (std::size_t k = 0; k < keyframes.size(); ++k) {
    // Its heading as the correction it now has: what the drift's checks measure against.
    keyframe_headings_[k] = wrap_angle(keyframe_headings_[k] + keyframes[k].turn);
    if (keyframes[k].turn != 0.0) map_uncertainty_.turn(k, keyframes[k].turn, drift_rate);
  }
  move_with_map(correction, yaw);
}

// The vehicle moved with its map: `moved` takes the old frame to the new, a turn of `yaw`.
void SlamPipeline::move_with_map(const Eigen::Isometry3d& moved, double yaw) {
  heading_correction_ = wrap_angle(heading_correction_ + yaw);
  free_space_.move(moved);
  pose_.position = moved * pose_.position;
  pose_.orientation = yaw_rotation(yaw) * pose_.orientation;
  last_map_update_position_ = moved * last_map_update_position_;
  last_map_update_heading_ = wrap_angle(last_map_update_heading_ + yaw);
}

std::vector<MapKeyframe> SlamPipeline::moved_keyframes(const Eigen::Isometry3d& moved,
                                                       std::size_t first) const {
  const std::vector<std::size_t>& starts = map_uncertainty_.first_points();
  std::vector<MapKeyframe> keyframes;
  for (std::size_t k = first; k < starts.size(); ++k) {
    const std::size_t end = k + 1 < starts.size() ? starts[k + 1] : map_.size();
    MapKeyframe keyframe;
    keyframe.position = moved * map_uncertainty_.positions()[k];
    for (std::size_t i = starts[k]; i < end; ++i) {
      keyframe.points.push_back(moved * map_.point(i));
      if (!map_.normals().empty()) keyframe.normals.push_back(moved.linear() * map_.normals()[i]);
    }
    keyframes.push_back(std::move(keyframe));
  }
  return keyframes;
}

// The map made again of its keyframes' points, in order, at their (moved) positions.
void SlamPipeline::rebuild_map(const std::vector<MapKeyframe>& keyframes) {
  map_ = WorldMap(make_nearest_neighbour_index(config_.nearest_neighbour),
                  config_.map.min_point_spacing);
  std::vector<std::size_t> first_points;
  std::vector<Vec3> positions;
  for (const MapKeyframe& keyframe : keyframes) {
    first_points.push_back(map_.size());
    positions.push_back(keyframe.position);
    map_.add_points(keyframe.points, keyframe.normals);
  }
  map_uncertainty_.move_keyframes(first_points, positions);
  nearest_.clear();  // the warm start's indices were the old map's
}

}  // namespace uavslam
