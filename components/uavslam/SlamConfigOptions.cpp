// The SLAM parameters a subcommand runs with: --config FILE, then each --set key=value.
#include <filesystem>

#include "Commands.hpp"
#include "io/SlamConfigFile.hpp"

namespace uavslam::cli {

std::string shipped_config(const std::string& name) {
  std::error_code error;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", error);
  if (!error) {
    // Installed: prefix/bin/uavslam beside prefix/config/.
    const std::filesystem::path installed = exe.parent_path().parent_path() / "config" / name;
    if (std::filesystem::exists(installed, error)) return installed.string();
  }
  return std::string(UAVSLAM_CONFIG_DIR) + "/" + name;
}

void add_slam_config_options(CLI::App& cmd, std::string& config,
                             std::vector<std::string>& overrides, const std::string& config_help) {
  cmd.add_option("--config", config, config_help)->check(CLI::ExistingFile);
  cmd.add_option("--set", overrides,
                 "override one SLAM parameter, e.g. --set icp.iterations=12 (repeatable)");
}

SlamConfig load_config(const std::string& path, const std::vector<std::string>& overrides) {
  SlamConfig config = path.empty() ? SlamConfig{} : io::load_slam_config(path);
  for (const std::string& assignment : overrides)
    io::apply_slam_config_override(config, assignment);
  return config;
}

}  // namespace uavslam::cli
