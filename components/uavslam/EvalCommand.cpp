// uavslam eval: trajectory errors of any estimate against a ground truth, both TUM files.
#include <iostream>

#include "Commands.hpp"
#include "RunSummary.hpp"
#include "io/TumFile.hpp"

namespace uavslam::cli {
namespace {

struct EvalOptions {
  std::string estimate;
  std::string ground_truth;
  std::string align = "none";
  double max_dt = 0.01;
  double delta = 1.0;
  bool json = false;
};

int run_eval(const EvalOptions& o) {
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
      "(RPE) of an estimate against a ground truth, both TUM files");
  cmd->add_option("--estimate", options->estimate, "estimated trajectory (TUM)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--groundtruth", options->ground_truth, "ground-truth trajectory (TUM)")
      ->required()
      ->check(CLI::ExistingFile);
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
  cmd->callback([options, &exit_code] { exit_code = run_eval(*options); });
}

}  // namespace uavslam::cli
