// How well the map itself is placed (beyond the seed). A match fixes the vehicle relative to the
// map points it paired with, and those points are only as well placed as the keyframe that added
// them was. So each keyframe keeps the covariance its pose had when it joined the map, over
// (x, y, z, yaw), and a match inherits its pairs' keyframes' covariances, each in the directions
// its pairs fixed. A keyframe's points are d_i = p_k + R(psi_k) b_i: an error (e_k, eps_k) of its
// pose moves them by e_k + eps_k perp(d_i - p_k) (perp(v) = (-v_y, v_x, 0): a turn about the
// vertical through p_k). By linear propagation through the normal equations (H t = sum_i J_i r_i)
// the match moves by
//   W_k e_k + g_k eps_k,   W_k = H^-1 H_k,   g_k = H^-1 sum_{i in k} H_i perp(d_i - p_k)
// (H_i: pair i's information, H_k the sum over k's pairs, H over all; the W_k sum to I), and the
// heading the map holds there is the keyframes' own, weighted by their share s_k of the
// horizontal information. Each keyframe's error is kept as the noises it came from
// (CorrelatedError: e_k = sum_j C_kj nu_j, its match's map part and its own match's noise), so
//   e = sum_k A_k e_k,   A_k = [W_k g_k; 0 s_k],   Sigma_map = Cov(e)
// shares exactly what the keyframes share: their common ancestry stays whole, their own noises
// average down. That is for a match of the translation only; one that turns the scan too takes a
// keyframe's turn about the vehicle as its own heading and keeps the shift e_k + eps_k perp(p -
// p_k), the lever arm to the vehicle, not to the walls (of_match's with_yaw). One keyframe gives
// its own covariance; a door edge seen only in a drifted keyframe gives that keyframe's along the
// corridor, however many wall pairs the anchor holds; a keyframe whose heading is uncertain gives a
// far match the lever arm's share of it (a map turned by eps about the take-off is off by eps x the
// distance from it). The first keyframe anchors the map's frame (zero). Exploring, a keyframe pairs
// with the last few and the covariance grows like a random walk; back in a known place the old
// keyframes' smaller one returns. It is the spanning tree of a pose graph's marginals (Olson's
// Dijkstra projection), without the loop edges that only a back end adds.
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <utility>
#include <vector>

#include "core/Correspondences.hpp"
#include "core/extensions/CorrelatedError.hpp"

namespace uavslam {

// What a match inherits of the map's error, over (x, y, z, yaw): the covariance its keyframes'
// own errors give (L L^T above), and apart, the error the heading's drift gives it, e = a r - h:
// the source's heading drifts at the rate r (rad/s), one for all keyframes, and a keyframe made
// dt after the first with the correction H (since the first's) is off by r dt - H; a and h are
// how the match moves with the two (a per rad/s). The rate is known as well as the heading
// checks know it (HeadingRate::Estimate), and only when the total is wanted: as the checks pin
// it down, the whole map is surer, its early keyframes and the positions they turned too.
struct MapError {
  CorrelatedError error;                              // e above
  Eigen::Vector4d drift = Eigen::Vector4d::Zero();    // a
  Eigen::Vector4d applied = Eigen::Vector4d::Zero();  // h
  Eigen::Matrix4d covariance() const { return error.covariance(); }
  // The whole covariance, given the rate r and its error's variance:
  //   Sigma + (a r - h)(a r - h)^T + var(r) a a^T
  Eigen::Matrix4d total(double rate, double rate_variance) const {
    const Eigen::Vector4d known = drift * rate - applied;
    return covariance() + known * known.transpose() + rate_variance * drift * drift.transpose();
  }
};

class MapUncertainty {
 public:
  // The noises an error keeps apart (CorrelatedError::prune): a room's worth of keyframes; 64
  // sources of 4 x 4 are 8 KB a keyframe.
  static constexpr std::size_t kSourcesKept = 64;

  // The keyframe whose points start at map index first_point, taken at body position `position`,
  // its own match's covariance over (x, y, z, yaw) (m^2, rad^2; a new noise, source k), its drift's
  // terms a and h (MapError; zero where the heading's drift is not modelled), and the error it
  // inherited from the map it matched (of_match's; none for the first, or a keyframe taken as
  // independent of the others).
  void add_keyframe(std::size_t first_point, const Vec3& position,
                    const Eigen::Matrix4d& own_covariance,
                    const Eigen::Vector4d& drift = Eigen::Vector4d::Zero(),
                    const Eigen::Vector4d& applied = Eigen::Vector4d::Zero(),
                    const CorrelatedError& inherited = {});
  // Keyframe k was turned by `turn` (rad) to where the drift's rate r puts it (HeadingRate::
  // turns): its correction grows by it, and its position, placed again on the turned map, carries
  // the drift as the rate says (h = a r there).
  void turn(std::size_t k, double turn, double rate);

  std::size_t keyframes() const { return first_points_.size(); }
  // Each keyframe's first point in the map, in keyframe order.
  const std::vector<std::size_t>& first_points() const { return first_points_; }
  // Each keyframe's body position, in keyframe order.
  const std::vector<Vec3>& positions() const { return positions_; }
  // Keyframe k's own error's covariance over (x, y, z, yaw): how well its points are placed.
  Eigen::Matrix4d keyframe_covariance(std::size_t k) const { return errors_[k].covariance(); }
  // The keyframe that added map point `index`; none before the first keyframe's points.
  std::optional<std::size_t> keyframe_of(std::size_t index) const;

  // The same keyframes, in the same order, now starting at these map indices and taken at these
  // positions (the map was rebuilt); throws std::invalid_argument for another count.
  void move_keyframes(const std::vector<std::size_t>& first_points,
                      const std::vector<Vec3>& positions);

  // Sigma_map above over (x, y, z, yaw) for the pairs (their map point and map_index, and the
  // information pair_joint_information gives them), with the drift's terms sum_k A_k a_k and
  // sum_k A_k h_k; zero when no pair holds information.
  // `position`: where the scan matched; scan_drift: the scan's own drift terms (its heading's a
  // and h: a scan turned by eps about the vehicle moves the match by -g eps, g = H^-1 sum_i H_i
  // perp(d_i - p), so a scan turned as its map is matches where a turned world would put it).
  // with_yaw: the match estimated its heading too (joint_match in the .cpp: a keyframe's turn
  // reaches it by the lever arm from that keyframe to the vehicle, and its yaw inherits the
  // keyframes' headings by their information); else its translation only, as above.
  MapError of_match(const Correspondences& pairs, const Vec3& position,
                    const Eigen::Vector2d& scan_drift = Eigen::Vector2d::Zero(),
                    bool with_yaw = false) const;
  // s_k above: each keyframe's share of the pairs' horizontal information, the weight its heading
  // has in the heading the map holds where the pairs are (keyframes with none left out).
  std::vector<std::pair<std::size_t, double>> heading_shares(const Correspondences& pairs) const;

 private:
  // What one keyframe's pairs hold of a match: H_k, sum_i H_i perp(d_i - p_k), and H4_k over
  // (x, y, z, yaw).
  struct KeyframePairs {
    Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
    Vec3 turn = Vec3::Zero();
    Eigen::Matrix4d joint = Eigen::Matrix4d::Zero();
  };
  struct Grouped {
    std::map<std::size_t, KeyframePairs> keyframes;
    Eigen::Matrix3d total = Eigen::Matrix3d::Zero();  // H
    Eigen::Matrix4d joint = Eigen::Matrix4d::Zero();  // H4
  };
  // position: the vehicle's, about which the match turns.
  Grouped by_keyframe(const Correspondences& pairs, const Vec3& position) const;
  void translation_match(const Grouped& grouped, const Vec3& position,
                         const Eigen::Vector2d& scan_drift, MapError& error) const;
  void joint_match(const Grouped& grouped, const Vec3& position, MapError& error) const;
  void add_keyframe_share(std::size_t k, const Eigen::Matrix4d& A, MapError& error) const;

  std::vector<std::size_t> first_points_;  // ascending
  std::vector<Vec3> positions_;            // p_k
  std::vector<CorrelatedError> errors_;    // e_k
  std::vector<Eigen::Vector4d> drifts_;    // a_k
  std::vector<Eigen::Vector4d> applied_;   // h_k
};

}  // namespace uavslam
