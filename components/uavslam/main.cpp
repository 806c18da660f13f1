// uavslam: simulate a flight and run the SLAM on it, evaluate trajectories, sweep parameters.
#include <iostream>
#include <stdexcept>

#include <CLI/CLI.hpp>

#include "Commands.hpp"
#include "common/StopRequest.hpp"
#include "io/FileError.hpp"
#include "io/YamlReader.hpp"

int main(int argc, char** argv) {
  CLI::App app{
      "uavslam: real-time LiDAR localisation and mapping for indoor UAVs (translation-only ICP "
      "with the orientation from the IMU, after the thesis design in ch. 5.4.3)"};
  app.require_subcommand(1);
  int exit_code = 0;
  uavslam::cli::add_simulate_command(app, exit_code);
  uavslam::cli::add_eval_command(app, exit_code);
  uavslam::cli::add_sweep_command(app, exit_code);
  uavslam::cli::add_launch_command(app, exit_code);
  uavslam::cli::add_report_command(app, exit_code);
  uavslam::cli::add_run_command(app, exit_code);
  uavslam::cli::add_offline_command(app, exit_code);
  uavslam::process::install_stop_handler();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;  // --help, or a bad flag or value (named by CLI11)
  } catch (const uavslam::io::ConfigError& e) {
    std::cerr << "uavslam: " << e.what() << "\n";
    return 2;
  } catch (const uavslam::io::FileError& e) {
    std::cerr << "uavslam: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "uavslam: " << e.what() << "\n";
    return 1;
  }
  return exit_code;
}
