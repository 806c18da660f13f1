// uavslam eval: trajectory errors of any estimate against a ground truth, both TUM files, or of
// a planar estimate against the Freiburg benchmark's relations (Kümmerle et al. 2009).
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>

#include "Commands.hpp"
#include "RunSummary.hpp"
#include "eval/RelationMetric.hpp"
#include "eval/ScanPairAlignment.hpp"
#include "io/CarmenLog.hpp"
#include "io/FileError.hpp"
#include "io/RelationsFile.hpp"
#include "io/TumFile.hpp"
#include "io/YamlReader.hpp"

namespace uavslam::cli {
namespace {

struct EvalOptions {
  std::string estimate;
  std::string ground_truth;
  std::string relations;
  std::string align = "none";
  double max_dt = 0.01;
  double delta = 1.0;
  bool json = false;
  bool consistency = false;
  std::string per_relation;  // a CSV file: each relation's errors
  std::string scans;         // a CARMEN log: align each relation's two scans (ScanPairAlignment)
  std::string config;
  std::vector<std::string> overrides;
};

constexpr double kDegreesPerRadian = 57.29577951308232;  // 180 / pi

nlohmann::json statistics_json(const eval::ErrorStatistics& s, double scale) {
  return {{"count", s.count},
          {"mean", s.mean * scale},
          {"std", s.std_dev * scale},
          {"max", s.max * scale}};
}

nlohmann::json subset_json(const eval::RelationSubsetErrors& e) {
  return {{"relations", e.relations},
          {"unmatched", e.unmatched},
          {"translation_m", statistics_json(e.translation, 1.0)},
          {"rotation_deg", statistics_json(e.rotation, kDegreesPerRadian)}};
}

void print_subset(std::ostream& out, const std::string& name, const eval::RelationSubsetErrors& e) {
  out << std::fixed << std::setprecision(4) << "  " << name << e.translation.mean << " ± "
      << e.translation.std_dev << " m (max " << e.translation.max << "), " << std::setprecision(3)
      << e.rotation.mean * kDegreesPerRadian << " ± " << e.rotation.std_dev * kDegreesPerRadian
      << " deg (max " << e.rotation.max * kDegreesPerRadian << ") over " << e.translation.count
      << " of " << e.relations << " relations, " << e.unmatched << " unmatched\n";
}

// Each relation's errors, a line each ("t1,t2,span_s,translation_m,rotation_deg,relation_m,
// along_m,across_m"; the errors empty for an unmatched relation, along and across also for one
// under 1 cm), to find where an estimate goes wrong.
void write_per_relation(const std::string& path, const eval::RelationErrors& errors) {
  std::ofstream out(path);
  if (!out) throw io::file_error(path, "cannot be written");
  out << "t1,t2,span_s,translation_m,rotation_deg,relation_m,along_m,across_m\n"
      << std::setprecision(10);
  for (const eval::RelationError& e : errors.each) {
    // Stamps to the logs' microsecond, whatever their epoch (Intel's are 976 052 905.167303 s).
    out << std::fixed << std::setprecision(6) << e.t1 << ',' << e.t2 << ',' << e.t2 - e.t1 << ','
        << std::defaultfloat << std::setprecision(10);
    if (e.translation) out << *e.translation;
    out << ',';
    if (e.rotation) out << *e.rotation * kDegreesPerRadian;
    out << ',' << e.length << ',';
    if (e.along) out << *e.along;
    out << ',';
    if (e.across) out << *e.across;
    out << '\n';
  }
  if (!out) throw io::file_error(path, "could not be written whole");
}

int run_relations_eval(const EvalOptions& o) {
  const eval::RelationErrors errors = eval::compare_to_relations(
      io::read_planar_estimate(o.estimate), io::read_relations(o.relations));
  if (!o.per_relation.empty()) write_per_relation(o.per_relation, errors);
  if (o.json) {
    const nlohmann::json j = {{"all", subset_json(errors.all)},
                              {"short_span_limit_s", errors.short_span_limit},
                              {"short_span", subset_json(errors.short_span)}};
    std::cout << j.dump(2) << "\n";
  } else {
    std::cout << "uavslam eval: " << o.estimate << " against the relations " << o.relations
              << " (Kuemmerle et al. 2009)\n";
    print_subset(std::cout, "all relations     ", errors.all);
    print_subset(std::cout, "under 5 s         ", errors.short_span);
  }
  return 0;
}

// The relations' triangles (eval/RelationMetric.hpp): how far the reference itself is from one
// trajectory.
int run_consistency(const EvalOptions& o) {
  const eval::RelationClosures c =
      eval::relation_triangle_closures(io::read_relations(o.relations));
  if (o.json) {
    const nlohmann::json j = {
        {"triangles", c.triangles},
        {"closure_translation_m", statistics_json(c.translation, 1.0)},
        {"closure_rotation_deg", statistics_json(c.rotation, kDegreesPerRadian)},
        {"triangles_with_a_short_leg", c.triangles_with_short_leg},
        {"short_span_limit_s", c.short_span_limit},
        {"short_leg_closure_translation_m", statistics_json(c.short_leg_translation, 1.0)}};
    std::cout << j.dump(2) << "\n";
    return 0;
  }
  std::cout << std::fixed << std::setprecision(4) << "uavslam eval: the relations " << o.relations
            << " against themselves\n  triangles         " << c.triangles << " close to within "
            << c.translation.mean << " ± " << c.translation.std_dev << " m (max "
            << c.translation.max << "), " << std::setprecision(3)
            << c.rotation.mean * kDegreesPerRadian << " ± "
            << c.rotation.std_dev * kDegreesPerRadian << " deg\n  with a leg under 5 s "
            << c.triangles_with_short_leg << ": " << std::setprecision(4)
            << c.short_leg_translation.mean << " ± " << c.short_leg_translation.std_dev << " m\n";
  return 0;
}

// The scans of a CARMEN log by stamp (the relations name scans by their ipc_timestamps), each with
// its own geometry (beam angles and the laser's mount).
class ScansByStamp {
 public:
  explicit ScansByStamp(const std::string& path) {
    const io::CarmenLog log = io::read_carmen_log(path);
    for (const std::string& problem : log.problems) std::cerr << problem << "\n";
    for (const io::CarmenMessage& message : log.messages) {
      if (const auto* scan = std::get_if<io::CarmenScan>(&message)) {
        scans_.emplace(key(scan->ipc_timestamp), *scan);
      }
    }
  }

  std::optional<Scan> at(double stamp) const {
    const auto found = scans_.find(key(stamp));
    if (found == scans_.end()) return std::nullopt;
    const io::CarmenScan& scan = found->second;
    return io::to_core_scan(scan, std::make_shared<const ScanGeometry>(io::to_scan_geometry(scan)),
                            0);
  }

 private:
  static long long key(double stamp) { return std::llround(stamp * 1e6); }  // the logs' 1 us
  std::map<long long, io::CarmenScan> scans_;
};

// Each relation's two scans aligned to each other from the relation (eval/ScanPairAlignment):
// how far the scans themselves put the relations.
int run_scan_pair_eval(const EvalOptions& o) {
  const SlamConfig config = load_config(o.config, o.overrides);
  const std::vector<eval::Relation> relations = io::read_relations(o.relations);
  const ScansByStamp scans(o.scans);
  std::vector<std::optional<eval::Relation>> aligned;
  std::size_t missing_scans = 0;
  for (const eval::Relation& relation : relations) {
    const std::optional<Scan> first = scans.at(relation.t1);
    const std::optional<Scan> second = scans.at(relation.t2);
    aligned.emplace_back();
    if (!first || !second) {
      ++missing_scans;
      continue;
    }
    const eval::ScanPairAlignment a = eval::align_scan_pair(*first, *second, relation, config);
    if (a.outcome == ScanOutcome::Accepted) aligned.back() = a.motion;
  }
  const eval::RelationErrors errors = eval::compare_relation_estimates(relations, aligned);
  if (!o.per_relation.empty()) write_per_relation(o.per_relation, errors);
  if (o.json) {
    const nlohmann::json j = {{"all", subset_json(errors.all)},
                              {"short_span_limit_s", errors.short_span_limit},
                              {"short_span", subset_json(errors.short_span)},
                              {"relations_without_their_scans", missing_scans}};
    std::cout << j.dump(2) << "\n";
    return 0;
  }
  std::cout << "uavslam eval: each relation's two scans of " << o.scans
            << " aligned to each other by the ICP, starting at the relation " << o.relations
            << "\n";
  print_subset(std::cout, "all relations     ", errors.all);
  print_subset(std::cout, "under 5 s         ", errors.short_span);
  std::cout << "  unmatched: " << missing_scans
            << " relations name a scan the log does not have; the rest the ICP rejected (scans "
               "that do not overlap)\n";
  return 0;
}

int run_eval(const EvalOptions& o) {
  if (!o.per_relation.empty() &&
      (o.relations.empty() || (o.estimate.empty() && o.scans.empty()) || o.consistency)) {
    throw io::ConfigError(
        "--per-relation lists each relation's errors: it needs --relations and --estimate or "
        "--scans");
  }
  if (!o.scans.empty()) {
    if (o.relations.empty()) throw io::ConfigError("--scans needs --relations");
    if (!o.estimate.empty() || o.consistency) {
      throw io::ConfigError("--scans scores the log's own scans: no --estimate or --consistency");
    }
    return run_scan_pair_eval(o);
  }
  if (o.consistency) {
    if (o.relations.empty()) throw io::ConfigError("--consistency needs --relations");
    return run_consistency(o);
  }
  if (o.estimate.empty()) throw io::ConfigError("--estimate is required");
  if (!o.relations.empty()) return run_relations_eval(o);
  eval::MetricOptions options;
  options.alignment = o.align == "se3" ? eval::Alignment::SE3 : eval::Alignment::None;
  options.max_time_difference = o.max_dt;
  options.rpe_delta = o.delta;
  const eval::TrajectoryErrors errors =
      eval::compare_trajectories(io::read_tum(o.estimate), io::read_tum(o.ground_truth), options);
  if (o.json) {
    std::cout << to_json(errors).dump(2) << "\n";
  } else {
    std::cout << "uavslam eval: " << o.estimate << " against " << o.ground_truth << " (alignment "
              << o.align << ")\n";
    print_errors(std::cout, errors);
  }
  return 0;
}

}  // namespace

void add_eval_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<EvalOptions>();
  CLI::App* cmd = app.add_subcommand(
      "eval",
      "Absolute trajectory error (ATE, horizontal and vertical) and relative pose error "
      "(RPE) of an estimate against a ground truth, both TUM files; or the Freiburg benchmark "
      "metric (Kuemmerle et al. 2009) of a planar estimate against relations");
  cmd->add_option("--estimate", options->estimate,
                  "estimated trajectory (TUM; with --relations 'timestamp x y theta' lines)")
      ->check(CLI::ExistingFile);
  // Exactly one reference: a ground-truth trajectory or the benchmark's relations.
  CLI::Option_group* reference =
      cmd->add_option_group("reference", "what the estimate is scored against");
  CLI::Option* ground_truth =
      reference->add_option("--groundtruth", options->ground_truth, "ground-truth trajectory (TUM)")
          ->check(CLI::ExistingFile);
  CLI::Option* relations =
      reference
          ->add_option("--relations", options->relations,
                       "true relative motions 't1 t2 x y z roll pitch yaw' (Freiburg benchmark)")
          ->check(CLI::ExistingFile)
          ->excludes(ground_truth);
  ground_truth->excludes(relations);
  reference->require_option(1);
  cmd->add_option("--align", options->align, "align the estimate first: none or se3 (Umeyama)")
      ->check(CLI::IsMember({"none", "se3"}))
      ->capture_default_str();
  cmd->add_option("--max-dt", options->max_dt, "largest stamp difference of a pose pair, s")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--delta", options->delta, "RPE time span, s")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_flag("--json", options->json, "print JSON instead of text");
  cmd->add_option("--per-relation", options->per_relation,
                  "with --relations and --estimate or --scans: write each relation's errors to "
                  "this CSV file (t1,t2,span_s,translation_m,rotation_deg,relation_m,along_m,"
                  "across_m: the translation error also split along and across the relation's "
                  "direction; the errors empty where unmatched)");
  cmd->add_flag("--consistency", options->consistency,
                "with --relations and no --estimate: how well the relations agree with each "
                "other (their triangles' closure: no estimate agrees with all three relations "
                "of a triangle that does not close)");
  cmd->add_option("--scans", options->scans,
                  "with --relations and no --estimate: a CARMEN log whose scans the relations "
                  "name; each relation's two scans are aligned to each other by the ICP, starting "
                  "at the relation, and scored against it (how far the scans themselves put the "
                  "relations: a floor for any estimate made from them)")
      ->check(CLI::ExistingFile);
  add_slam_config_options(*cmd, options->config, options->overrides,
                          "with --scans: SLAM parameters YAML for the ICP (e.g. "
                          "config/slam_2d_logs.yaml; default: the built-in defaults)");
  cmd->callback([options, &exit_code] { exit_code = run_eval(*options); });
}

}  // namespace uavslam::cli
