#include "io/SlamConfigFile.hpp"

#include <iterator>
#include <vector>

#include "io/YamlReader.hpp"

namespace uavslam::io {

namespace {

// A mode's value: one of the names of its table (core/SlamConfig.hpp), any other word refused
// with those names.
template <typename Mode>
Mode as_mode(const YamlReader& value) {
  std::vector<std::string> names;
  for (const auto& [name, mode] : ModeNames<Mode>::all) names.emplace_back(name);
  const std::string chosen = value.as_choice(names);
  for (const auto& [name, mode] : ModeNames<Mode>::all) {
    if (name == chosen) return mode;
  }
  return ModeNames<Mode>::all.front().second;  // not reached: as_choice refused it
}

// One settable parameter: where it lives in the file and how its value is checked and stored.
// The file loader and the command-line override share this table, so they cannot disagree.
struct Parameter {
  const char* section;
  const char* key;
  void (*set)(SlamConfig&, const YamlReader& value);

  std::string path() const { return std::string(section) + "." + key; }
};

// The keys in two lists, the scan, matcher and map's and those of the extensions beyond them: as
// one list this long, clang-format gives up laying its lambdas out.
std::vector<Parameter> matcher_parameters() {
  return {
      {"scan", "subsample_every",
       [](SlamConfig& c, const YamlReader& v) {
         c.scan.subsample_every = v.as_int(NumberRange::at_least(1));
       }},
      {"scan", "floor_margin",
       [](SlamConfig& c, const YamlReader& v) {
         c.scan.floor_margin = v.as_double(NumberRange::non_negative());
       }},
      {"scan", "deskew", [](SlamConfig& c, const YamlReader& v) { c.scan.deskew = v.as_bool(); }},
      {"floor", "level_gate",
       [](SlamConfig& c, const YamlReader& v) {
         c.floor.level_gate = v.as_double(NumberRange::non_negative());
       }},
      {"floor", "level_window",
       [](SlamConfig& c, const YamlReader& v) {
         c.floor.level_window = v.as_double(NumberRange::non_negative());
       }},
      {"floor", "flatness",
       [](SlamConfig& c, const YamlReader& v) {
         c.floor.flatness = v.as_double(NumberRange::non_negative());
       }},
      {"icp", "iterations",
       [](SlamConfig& c, const YamlReader& v) {
         c.icp.iterations = v.as_int(NumberRange::at_least(1));
       }},
      {"icp", "max_translation",
       [](SlamConfig& c, const YamlReader& v) {
         c.icp.max_translation = v.as_double(NumberRange::non_negative());
       }},
      {"icp", "max_error_after",
       [](SlamConfig& c, const YamlReader& v) {
         c.icp.max_error_after = v.as_double(NumberRange::non_negative());
       }},
      {"icp", "max_error_ratio",
       [](SlamConfig& c, const YamlReader& v) {
         c.icp.max_error_ratio = v.as_double(NumberRange::non_negative());
       }},
      {"icp", "max_correspondence_distance",
       [](SlamConfig& c, const YamlReader& v) {
         c.icp.max_correspondence_distance = v.as_double(NumberRange::non_negative());
       }},
      {"icp", "split_axes",
       [](SlamConfig& c, const YamlReader& v) { c.icp.split_axes = v.as_bool(); }},
      {"icp", "motion_prior",
       [](SlamConfig& c, const YamlReader& v) { c.icp.motion_prior = as_mode<MotionPrior>(v); }},
      {"icp", "heading",
       [](SlamConfig& c, const YamlReader& v) { c.icp.heading = as_mode<HeadingMode>(v); }},
      {"icp", "heading_check_every",
       [](SlamConfig& c, const YamlReader& v) {
         c.icp.heading_check_every = v.as_int(NumberRange::at_least(1));
       }},
      {"icp", "heading_check_tolerance",
       [](SlamConfig& c, const YamlReader& v) {
         c.icp.heading_check_tolerance = v.as_double(NumberRange::non_negative());
       }},
      {"icp", "heading_anchor",
       [](SlamConfig& c, const YamlReader& v) {
         c.icp.heading_anchor = v.as_double(NumberRange::non_negative());
       }},
      {"icp", "heading_max_tilt",
       [](SlamConfig& c, const YamlReader& v) {
         c.icp.heading_max_tilt = v.as_double(NumberRange::non_negative());
       }},
      {"icp", "max_rotation",
       [](SlamConfig& c, const YamlReader& v) {
         c.icp.max_rotation = v.as_double(NumberRange::non_negative());
       }},
      {"icp", "metric",
       [](SlamConfig& c, const YamlReader& v) { c.icp.metric = as_mode<IcpMetric>(v); }},
      {"icp", "prior_weight",
       [](SlamConfig& c, const YamlReader& v) {
         c.icp.prior_weight = v.as_double(NumberRange::non_negative());
       }},
      {"icp", "refine_lines_only",
       [](SlamConfig& c, const YamlReader& v) { c.icp.refine_lines_only = v.as_bool(); }},
      {"icp", "robust_scale",
       [](SlamConfig& c, const YamlReader& v) {
         c.icp.robust_scale = v.as_double(NumberRange::non_negative());
       }},
      {"icp", "refine_iterations",
       [](SlamConfig& c, const YamlReader& v) {
         c.icp.refine_iterations = v.as_int(NumberRange::at_least(1));
       }},
      {"icp", "stop_step",
       [](SlamConfig& c, const YamlReader& v) {
         c.icp.stop_step = v.as_double(NumberRange::non_negative());
       }},
      {"icp", "prior_gate",
       [](SlamConfig& c, const YamlReader& v) {
         c.icp.prior_gate = v.as_double(NumberRange::non_negative());
       }},
      {"icp", "prior_gate_overrule",
       [](SlamConfig& c, const YamlReader& v) {
         c.icp.prior_gate_overrule = v.as_int(NumberRange::non_negative());
       }},
      {"nearest_neighbour", "index",
       [](SlamConfig& c, const YamlReader& v) {
         c.nearest_neighbour.index = as_mode<IndexKind>(v);
       }},
      {"nearest_neighbour", "flann_trees",
       [](SlamConfig& c, const YamlReader& v) {
         c.nearest_neighbour.flann_trees = v.as_int(NumberRange::at_least(1));
       }},
      {"nearest_neighbour", "flann_checks",
       [](SlamConfig& c, const YamlReader& v) {
         c.nearest_neighbour.flann_checks = v.as_int(NumberRange::at_least(1));
       }},
      {"map", "subsample_every",
       [](SlamConfig& c, const YamlReader& v) {
         c.map.subsample_every = v.as_int(NumberRange::at_least(1));
       }},
      {"map", "keyframe_height",
       [](SlamConfig& c, const YamlReader& v) {
         c.map.keyframe_height = v.as_double(NumberRange::non_negative());
       }},
      {"map", "keyframe_lateral",
       [](SlamConfig& c, const YamlReader& v) {
         c.map.keyframe_lateral = v.as_double(NumberRange::non_negative());
       }},
      {"map", "keyframe_rotation",
       [](SlamConfig& c, const YamlReader& v) {
         c.map.keyframe_rotation = v.as_double(NumberRange::non_negative());
       }},
      {"map", "min_point_spacing",
       [](SlamConfig& c, const YamlReader& v) {
         c.map.min_point_spacing = v.as_double(NumberRange::non_negative());
       }},
      {"recovery", "gap",
       [](SlamConfig& c, const YamlReader& v) {
         c.recovery.gap = v.as_double(NumberRange::non_negative());
       }},
      {"recovery", "max_speed",
       [](SlamConfig& c, const YamlReader& v) {
         c.recovery.max_speed = v.as_double(NumberRange::non_negative());
       }},
      {"recovery", "max_radius",
       [](SlamConfig& c, const YamlReader& v) {
         c.recovery.max_radius = v.as_double(NumberRange::non_negative());
       }},
      {"recovery", "grid_step",
       [](SlamConfig& c, const YamlReader& v) {
         c.recovery.grid_step = v.as_double(NumberRange::positive());
       }},
  };
}

std::vector<Parameter> extension_parameters() {
  return {
      {"free_space", "enabled",
       [](SlamConfig& c, const YamlReader& v) { c.free_space.enabled = v.as_bool(); }},
      {"free_space", "resolution",
       [](SlamConfig& c, const YamlReader& v) {
         c.free_space.resolution = v.as_double(NumberRange::positive());
       }},
      {"free_space", "reach",
       [](SlamConfig& c, const YamlReader& v) {
         c.free_space.reach = v.as_double(NumberRange::positive());
       }},
      {"free_space", "memory",
       [](SlamConfig& c, const YamlReader& v) {
         c.free_space.memory = v.as_double(NumberRange::positive());
       }},
      {"free_space", "min_passes",
       [](SlamConfig& c, const YamlReader& v) {
         c.free_space.min_passes = v.as_int(NumberRange::between(1, 255));
       }},
      {"degeneracy", "threshold",
       [](SlamConfig& c, const YamlReader& v) {
         c.degeneracy.threshold = v.as_double(NumberRange::non_negative());
       }},
      {"degeneracy", "min_sigma",
       [](SlamConfig& c, const YamlReader& v) {
         c.degeneracy.min_sigma = v.as_double(NumberRange::positive());
       }},
      {"degeneracy", "hold_blind_yaw",
       [](SlamConfig& c, const YamlReader& v) { c.degeneracy.hold_blind_yaw = v.as_bool(); }},
      {"degeneracy", "search_window",
       [](SlamConfig& c, const YamlReader& v) {
         c.degeneracy.search_window = v.as_double(NumberRange::non_negative());
       }},
      {"degeneracy", "search_step",
       [](SlamConfig& c, const YamlReader& v) {
         c.degeneracy.search_step = v.as_double(NumberRange::positive());
       }},
      {"degeneracy", "search_sigma",
       [](SlamConfig& c, const YamlReader& v) {
         c.degeneracy.search_sigma = v.as_double(NumberRange::positive());
       }},
      {"degeneracy", "search_uniqueness",
       [](SlamConfig& c, const YamlReader& v) {
         c.degeneracy.search_uniqueness = v.as_double(NumberRange::between(0.0, 1.0));
       }},
      {"motion", "accel_noise_density",
       [](SlamConfig& c, const YamlReader& v) {
         c.motion.accel_noise_density = v.as_double(NumberRange::non_negative());
       }},
      {"motion", "accel_bias_walk",
       [](SlamConfig& c, const YamlReader& v) {
         c.motion.accel_bias_walk = v.as_double(NumberRange::non_negative());
       }},
      {"motion", "initial_speed_sigma",
       [](SlamConfig& c, const YamlReader& v) {
         c.motion.initial_speed_sigma = v.as_double(NumberRange::non_negative());
       }},
      {"motion", "initial_bias_sigma",
       [](SlamConfig& c, const YamlReader& v) {
         c.motion.initial_bias_sigma = v.as_double(NumberRange::non_negative());
       }},
      {"motion", "match_error_sigma",
       [](SlamConfig& c, const YamlReader& v) {
         c.motion.match_error_sigma = v.as_double(NumberRange::non_negative());
       }},
      {"motion", "match_error_distance",
       [](SlamConfig& c, const YamlReader& v) {
         c.motion.match_error_distance = v.as_double(NumberRange::positive());
       }},
      {"motion", "odometry_noise_per_metre",
       [](SlamConfig& c, const YamlReader& v) {
         c.motion.odometry_noise_per_metre = v.as_double(NumberRange::non_negative());
       }},
      {"motion", "odometry_noise_floor",
       [](SlamConfig& c, const YamlReader& v) {
         c.motion.odometry_noise_floor = v.as_double(NumberRange::non_negative());
       }},
      {"motion", "fuse_velocity",
       [](SlamConfig& c, const YamlReader& v) { c.motion.fuse_velocity = v.as_bool(); }},
      {"imu", "max_gap",
       [](SlamConfig& c, const YamlReader& v) {
         c.imu.max_gap = v.as_double(NumberRange::positive());
       }},
      {"imu", "attitude_sigma",
       [](SlamConfig& c, const YamlReader& v) {
         c.imu.attitude_sigma = v.as_double(NumberRange::positive());
       }},
      {"imu", "heading_sigma",
       [](SlamConfig& c, const YamlReader& v) {
         c.imu.heading_sigma = v.as_double(NumberRange::positive());
       }},
      {"imu", "heading_drift_sigma",
       [](SlamConfig& c, const YamlReader& v) {
         c.imu.heading_drift_sigma = v.as_double(NumberRange::non_negative());
       }},
      {"loop_closure", "enabled",
       [](SlamConfig& c, const YamlReader& v) { c.loop_closure.enabled = v.as_bool(); }},
      {"loop_closure", "step_sigma",
       [](SlamConfig& c, const YamlReader& v) {
         c.loop_closure.step_sigma = v.as_double(NumberRange::positive());
       }},
      {"loop_closure", "step_sigma_per_metre",
       [](SlamConfig& c, const YamlReader& v) {
         c.loop_closure.step_sigma_per_metre = v.as_double(NumberRange::non_negative());
       }},
      {"loop_closure", "step_yaw_sigma",
       [](SlamConfig& c, const YamlReader& v) {
         c.loop_closure.step_yaw_sigma = v.as_double(NumberRange::positive());
       }},
      {"loop_closure", "step_yaw_sigma_per_radian",
       [](SlamConfig& c, const YamlReader& v) {
         c.loop_closure.step_yaw_sigma_per_radian = v.as_double(NumberRange::non_negative());
       }},
      {"loop_closure", "loop_sigma",
       [](SlamConfig& c, const YamlReader& v) {
         c.loop_closure.loop_sigma = v.as_double(NumberRange::positive());
       }},
      {"loop_closure", "loop_yaw_sigma",
       [](SlamConfig& c, const YamlReader& v) {
         c.loop_closure.loop_yaw_sigma = v.as_double(NumberRange::positive());
       }},
      {"loop_closure", "min_travel",
       [](SlamConfig& c, const YamlReader& v) {
         c.loop_closure.min_travel = v.as_double(NumberRange::non_negative());
       }},
      {"loop_closure", "min_radius",
       [](SlamConfig& c, const YamlReader& v) {
         c.loop_closure.min_radius = v.as_double(NumberRange::positive());
       }},
      {"loop_closure", "max_radius",
       [](SlamConfig& c, const YamlReader& v) {
         c.loop_closure.max_radius = v.as_double(NumberRange::positive());
       }},
      {"loop_closure", "known_radius",
       [](SlamConfig& c, const YamlReader& v) {
         c.loop_closure.known_radius = v.as_double(NumberRange::non_negative());
       }},
      {"loop_closure", "max_candidates",
       [](SlamConfig& c, const YamlReader& v) {
         c.loop_closure.max_candidates = v.as_int(NumberRange::at_least(1));
       }},
      {"loop_closure", "submap_keyframes",
       [](SlamConfig& c, const YamlReader& v) {
         c.loop_closure.submap_keyframes = v.as_int(NumberRange::non_negative());
       }},
      {"loop_closure", "resolution",
       [](SlamConfig& c, const YamlReader& v) {
         c.loop_closure.resolution = v.as_double(NumberRange::positive());
       }},
      {"loop_closure", "min_score",
       [](SlamConfig& c, const YamlReader& v) {
         c.loop_closure.min_score = v.as_double(NumberRange::between(0.0, 1.0));
       }},
      {"loop_closure", "min_score_margin",
       [](SlamConfig& c, const YamlReader& v) {
         c.loop_closure.min_score_margin = v.as_double(NumberRange::non_negative());
       }},
      {"loop_closure", "max_opposed_share",
       [](SlamConfig& c, const YamlReader& v) {
         c.loop_closure.max_opposed_share = v.as_double(NumberRange::between(0.0, 1.0));
       }},
      {"loop_closure", "ambiguity_radius",
       [](SlamConfig& c, const YamlReader& v) {
         c.loop_closure.ambiguity_radius = v.as_double(NumberRange::positive());
       }},
  };
}

const std::vector<Parameter>& parameters() {
  static const std::vector<Parameter> table = [] {
    std::vector<Parameter> all = matcher_parameters();
    std::vector<Parameter> more = extension_parameters();
    all.insert(all.end(), std::make_move_iterator(more.begin()),
               std::make_move_iterator(more.end()));
    return all;
  }();
  return table;
}

std::vector<std::string> section_names() {
  std::vector<std::string> names;
  for (const Parameter& p : parameters()) {
    if (names.empty() || names.back() != p.section) names.emplace_back(p.section);
  }
  return names;
}

std::vector<std::string> key_names(const std::string& section) {
  std::vector<std::string> names;
  for (const Parameter& p : parameters()) {
    if (section == p.section) names.emplace_back(p.key);
  }
  return names;
}

std::vector<std::string> parameter_paths() {
  std::vector<std::string> paths;
  for (const Parameter& p : parameters()) paths.push_back(p.path());
  return paths;
}

}  // namespace

SlamConfig load_slam_config(const std::string& path) {
  const YamlReader root = YamlReader::from_file(path, "SLAM config");
  root.expect_keys_only(section_names());
  for (const std::string& section : section_names()) {
    if (const auto reader = root.find(section)) reader->expect_keys_only(key_names(section));
  }
  SlamConfig config;
  for (const Parameter& p : parameters()) {
    const auto section = root.find(p.section);
    if (!section) continue;
    if (const auto value = section->find(p.key)) p.set(config, *value);
  }
  return config;
}

void apply_slam_config_override(SlamConfig& config, const std::string& assignment) {
  const std::string source = "--set '" + assignment + "'";
  const std::size_t equals = assignment.find('=');
  if (equals == std::string::npos) {
    throw ConfigError(source + ": expected section.key=value, e.g. icp.iterations=12");
  }
  const std::string path = assignment.substr(0, equals);
  for (const Parameter& p : parameters()) {
    if (p.path() != path) continue;
    p.set(config, YamlReader::from_text(assignment.substr(equals + 1), source, path));
    return;
  }
  std::string known;
  for (const std::string& name : parameter_paths()) known += (known.empty() ? "" : ", ") + name;
  throw ConfigError(source + ": unknown key '" + path + "' (known keys: " + known + ")");
}

}  // namespace uavslam::io
