// The `uavslam` tool end to end: it is run as a user would, on the shipped scenarios and config,
// and its files are read back with the project's own readers.
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iterator>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "TempDirTest.hpp"
#include "io/McapReader.hpp"
#include "io/McapWriter.hpp"
#include "io/OctreeFile.hpp"
#include "io/PcdFile.hpp"
#include "io/PlyFile.hpp"
#include "io/TumFile.hpp"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

CommandResult run(const std::string& arguments) {
  const std::string command = std::string(UAVSLAM_BINARY) + " " + arguments + " 2>&1";
  CommandResult result;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return result;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe)) result.output += buffer;
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

std::string source(const std::string& relative) {
  return std::string(UAVSLAM_SOURCE_DIR) + "/" + relative;
}

using UavslamCli = uavslam::test::TempDirTest;

// `uavslam simulate` of a shipped scenario into out; its summary.json.
nlohmann::json simulate(const fs::path& out, const std::string& scenario, const std::string& config,
                        const std::string& options = "") {
  // A shipped scenario's name, or a path to a scenario of the test's own.
  const std::string file = scenario.find('/') == std::string::npos
                               ? source("config/scenarios/" + scenario + ".yaml")
                               : scenario;
  const CommandResult r = run("simulate --quiet --scenario " + file + " --config " +
                              source(config) + " " + options + " --out " + out.string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  std::ifstream json_file(out / "summary.json");
  return nlohmann::json::parse(json_file);
}

// A shipped scenario as flown before the scenarios swept (lidar.sweep_seconds): every beam at the
// scan's stamp, into dir; the path, for simulate().
std::string without_sweep(const std::string& scenario, const fs::path& dir) {
  std::ifstream shipped(source("config/scenarios/" + scenario + ".yaml"));
  const fs::path copy = dir / (scenario + "_unswept.yaml");
  std::ofstream out(copy);
  for (std::string line; std::getline(shipped, line);) {
    if (line.find("sweep_seconds:") == std::string::npos) out << line << '\n';
  }
  return copy.string();
}

// A copy of a shipped scenario in `dir` whose IMU has the accelerometer bias `bias` (m/s^2 per
// body axis, as scenarios write it: "[x, y, z]").
std::string with_accel_bias(const std::string& scenario, const std::string& bias,
                            const fs::path& dir) {
  std::ifstream shipped(source("config/scenarios/" + scenario + ".yaml"));
  const fs::path copy = dir / (scenario + "_biased.yaml");
  std::ofstream out(copy);
  for (std::string line; std::getline(shipped, line);) {
    if (line.find("accel_bias:") != std::string::npos) continue;
    out << line << '\n';
    if (line.rfind("imu:", 0) == 0) out << "  accel_bias: " << bias << '\n';
  }
  return copy.string();
}

// The Freiburg logs, where the machine has them.
const fs::path kFreiburg = fs::path(UAVSLAM_SOURCE_DIR) / ".." / "shared" / "data" / "freiburg";

struct RealLogRun {
  std::string output;        // what `uavslam run` printed
  nlohmann::json summary;    // its summary.json
  nlohmann::json relations;  // `uavslam eval --json` of its estimate against the relations
};

// `uavslam run` of Freiburg log `log` with the shipped 2D-logs config into out, and its estimate
// scored against the log's relations; none when either command fails (a failure is recorded).
std::optional<RealLogRun> run_real_log(const std::string& log, const fs::path& out) {
  const CommandResult r =
      run("run --quiet --carmen " + (kFreiburg / (log + ".clf")).string() + " --out " +
          out.string() + " --config " + source("config/slam_2d_logs.yaml"));
  if (r.exit_code != 0) {
    ADD_FAILURE() << "uavslam run exit " << r.exit_code << ":\n" << r.output;
    return std::nullopt;
  }
  const CommandResult e =
      run("eval --json --relations " + (kFreiburg / (log + ".relations")).string() +
          " --estimate " + (out / "estimate.txt").string());
  if (e.exit_code != 0) {
    ADD_FAILURE() << "uavslam eval exit " << e.exit_code << ":\n" << e.output;
    return std::nullopt;
  }
  std::ifstream json(out / "summary.json");
  return RealLogRun{r.output, nlohmann::json::parse(json), nlohmann::json::parse(e.output)};
}

// One line of simulate's scans.csv, split at its commas (a trailing empty field, nees without a
// covariance, is dropped).
std::vector<std::string> fields_of(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream row(line);
  for (std::string field; std::getline(row, field, ',');) fields.push_back(field);
  return fields;
}

double ate_horizontal(const nlohmann::json& summary) {
  return summary.at("trajectory_errors").at("ate_horizontal_rmse_m").get<double>();
}

// A shipped scenario flown with noise seeds 1-4 as config/slam.yaml ships and with the blind axis
// not searched (degeneracy.search_window=0): the searched flights' summaries and each way's mean
// horizontal ATE.
struct SearchedAndCarried {
  std::vector<nlohmann::json> searched_flights;
  double searched = 0.0;
  double carried = 0.0;
};

SearchedAndCarried fly_searched_and_carried(const fs::path& dir, const std::string& scenario) {
  constexpr int kSeeds = 4;
  SearchedAndCarried flown;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    const std::string noise = "--seed " + std::to_string(seed);
    const std::string name = scenario + std::to_string(seed);
    flown.searched_flights.push_back(simulate(dir / name, scenario, "config/slam.yaml", noise));
    flown.searched += ate_horizontal(flown.searched_flights.back()) / kSeeds;
    flown.carried += ate_horizontal(simulate(dir / (name + "carried"), scenario, "config/slam.yaml",
                                             noise + " --set degeneracy.search_window=0")) /
                     kSeeds;
  }
  return flown;
}

// The horizontal ATE of `scenario` flown with config/slam.yaml and `options`, averaged over the
// noise seeds 1 to `seeds` (each into out/seedN).
double mean_ate(const fs::path& out, const std::string& scenario, const std::string& options,
                int seeds) {
  double mean = 0.0;
  for (int seed = 1; seed <= seeds; ++seed) {
    const std::string name = "seed" + std::to_string(seed);
    mean += ate_horizontal(simulate(out / name, scenario, "config/slam.yaml",
                                    options + " --seed " + std::to_string(seed))) /
            seeds;
  }
  return mean;
}

TEST_F(UavslamCli, SimulateTracksTheShortFlightAndWritesEveryOutput) {
  const fs::path out = dir / "out";
  const CommandResult r =
      run("simulate --quiet --scenario " + source("config/scenarios/short.yaml") + " --config " +
          source("config/slam.yaml") + " --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("ATE RMSE"));

  std::ifstream json_file(out / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(json_file);
  const auto& errors = summary.at("trajectory_errors");
  EXPECT_LT(errors.at("ate_horizontal_rmse_m").get<double>(), 0.10);
  EXPECT_LT(errors.at("ate_vertical_rmse_m").get<double>(), 0.10);
  const std::size_t scans = summary.at("scans").at("in");
  const std::size_t accepted = summary.at("scans").at("accepted");
  EXPECT_EQ(scans, 801u);  // 20 s at 40 Hz, both ends included
  EXPECT_GE(accepted, scans * 9 / 10);

  EXPECT_EQ(uavslam::io::read_tum((out / "estimate.tum").string()).size(), accepted);
  EXPECT_EQ(uavslam::io::read_tum((out / "groundtruth.tum").string()).size(), scans);
  EXPECT_EQ(uavslam::io::read_ply((out / "map.ply").string()).size(),
            summary.at("map").at("points").get<std::size_t>());
  std::ifstream csv(out / "scans.csv");
  std::size_t lines = 0;
  for (std::string line; std::getline(csv, line);) ++lines;
  EXPECT_EQ(lines, scans + 1);

  // eval on the written files reproduces the summary's figure.
  const CommandResult e = run("eval --json --estimate " + (out / "estimate.tum").string() +
                              " --groundtruth " + (out / "groundtruth.tum").string());
  ASSERT_EQ(e.exit_code, 0) << e.output;
  const nlohmann::json evaluated = nlohmann::json::parse(e.output);
  EXPECT_NEAR(evaluated.at("ate_horizontal_rmse_m").get<double>(),
              errors.at("ate_horizontal_rmse_m").get<double>(), 1e-5);
}

// Issue 17's corridor (config/scenarios/plain_corridor.yaml): 2 m wide, plain, the far end out of
// range, the IMU's heading drifting. The seed holds the take-off point and calls every scan a
// match; the UAV's config carries the vehicle down the corridor on the IMU's accelerations and
// says the axis is blind, in the tracking state too.
TEST_F(UavslamCli, ThePlainCorridorsAxisIsFlaggedAndCarriedByTheImu) {
  EXPECT_GT(ate_horizontal(simulate(dir / "seed", "plain_corridor", "config/seed.yaml")), 3.0);

  const fs::path uav_out = dir / "uav";
  const nlohmann::json uav = simulate(uav_out, "plain_corridor", "config/slam.yaml");
  // Issue 17's targets over flights with noise seeds 1 to 8, where the axis is lost by a chaotic
  // few centimetres more or less (the scenario's own seed, 3: 0.111 m, the mean 0.075 m; 16
  // seeds 0.056 m, test/bench/monte_carlo.sh): the ATE, and the covariance (the match's, the
  // map's, the IMU's along the axis) covering the error, NEES averaging within [0.5, 2] x the 3
  // dimensions (one flight's NEES varies from about 1 to 8 over 16 seeds: docs/algorithm.md).
  // The NEES with the height chained through the map (floor.level_gate=0): with the height from
  // the floor's level, as shipped, the shipped config is NOT within the target here (16 seeds:
  // 1.1): the chained height's error had made up for the horizontal covariance's caution (the
  // axis carried with an accelerometer bias the simulator's IMU lacks, the map's y several times
  // its error). Issue 17 stays open on it; docs/algorithm.md#the-height-from-the-take-off-floors-
  // level-shipped.
  constexpr int kSeeds = 8;
  double ate = 0.0;
  double nees = 0.0;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    const std::string name = "seed" + std::to_string(seed);
    const std::string noise = "--seed " + std::to_string(seed);
    ate +=
        ate_horizontal(simulate(dir / name, "plain_corridor", "config/slam.yaml", noise)) / kSeeds;
    const nlohmann::json chained =
        simulate(dir / (name + "chained"), "plain_corridor", "config/slam.yaml",
                 noise + " --set floor.level_gate=0");
    nees += chained.at("consistency").at("nees_mean").get<double>() / kSeeds;
  }
  EXPECT_LE(ate, 0.10);
  EXPECT_GE(nees, 1.5);
  EXPECT_LE(nees, 6.0);
  // Airborne scans (above 1 m) see one degenerate direction: the corridor's axis.
  std::ifstream csv(uav_out / "scans.csv");
  std::string line;
  std::getline(csv, line);
  std::size_t airborne = 0;
  std::size_t flagged = 0;
  while (std::getline(csv, line)) {
    const std::vector<std::string> fields = fields_of(line);
    ASSERT_GE(fields.size(), 22u) << line;  // the last, nees, is empty without a covariance
    if (fields[1] != "accepted" || std::stod(fields[12]) < 1.0) continue;
    ++airborne;
    // Said as the matcher_status says it: degraded, because a direction is degenerate.
    flagged += fields[14] == "1" && fields[20] == "degraded" && fields[21] == "degenerate";
  }
  EXPECT_GT(airborne, 500u);
  EXPECT_GE(flagged, airborne * 95 / 100);
  // Nothing across the axis but the end wall behind, out of view: nothing the search may take.
  EXPECT_EQ(uav.at("scans").at("blind_fixed").get<int>(), 0);
  EXPECT_GE(uav.at("tracking").at("by_reason").at("degraded: degenerate").get<std::size_t>(),
            flagged);
}

// The plain corridor with a real accelerometer's bias (3.5 mg along the axis) and nothing to fix
// the axis: lost by metres, as any IMU alone would be, but the covariance must say so. The prior's
// spread along the map's axis is turned by the map's heading error; judged along the map's axis
// alone, the error showed across it against centimetres (NEES 18.2 on this flight, 5514 on seed
// 5; now 2.1).
TEST_F(UavslamCli, ACorridorLostAlongItsAxisIsAsUncertainAsItIsOff) {
  const nlohmann::json lost =
      simulate(dir / "lost", with_accel_bias("plain_corridor", "[-0.035, -0.034, 0.020]", dir),
               "config/slam.yaml");
  EXPECT_GT(ate_horizontal(lost), 1.0) << "the test means a flight lost along the axis";
  EXPECT_LE(lost.at("consistency").at("nees_mean").get<double>(), 6.0);
}

// The corridor with door recesses (corridor.yaml): its axis is blind but for the door edges. An
// edge fixes the axis against keyframes the IMU carried there, and the axis is blind again a few
// scans later: the covariance must still hold how well those keyframes were placed (before, it
// kept only the filter's map-relative part there, and the NEES averaged 1852).
TEST_F(UavslamCli, ADoorEdgesFixLeavesTheCorridorsAxisAsUncertainAsItsMap) {
  const nlohmann::json uav = simulate(dir / "uav", "corridor", "config/slam.yaml");
  EXPECT_LE(uav.at("consistency").at("nees_mean").get<double>(), 6.0);
}

// The corridor furnished with cabinets (furnished_corridor.yaml): the take-off's scans fix the
// axis on the cabinets' ends until they climb past their tops, and those last fixes drift together
// by a centimetre or two. Taken as independent (motion.match_error_sigma 0) they wrote a velocity
// and a bias the filter was sure of, flown on down the blind axis (seed 12: 0.42 m off, NEES 80);
// with the matches' shared error a state of the inertial filter's, it says how little they told,
// and the search along the axis, over the wider spread, fixes it again.
TEST_F(UavslamCli, MatchesThatDriftTogetherAreNoAccelerationTheFilterIsSureOf) {
  const nlohmann::json independent =
      simulate(dir / "independent", "furnished_corridor", "config/slam.yaml",
               "--seed 12 --set motion.match_error_sigma=0");
  const nlohmann::json shared =
      simulate(dir / "shared", "furnished_corridor", "config/slam.yaml", "--seed 12");
  EXPECT_GT(independent.at("consistency").at("nees_mean").get<double>(), 6.0)
      << "the test means a flight the drifting fixes misled";
  EXPECT_LE(shared.at("consistency").at("nees_mean").get<double>(), 6.0);
  EXPECT_LT(ate_horizontal(shared), 0.5 * ate_horizontal(independent));
}

// The corridor flown with a real accelerometer's bias (biased_corridor.yaml): at take-off the
// axis is blind but for door jambs and pilasters far ahead, and the bias integrated there is built
// into the map. Searched along the axis, the jambs in the take-off's keyframes fix it (seeds 1-4:
// 0.500 -> 0.061 m; 16 seeds in docs/algorithm.md), and the covariance stays honest about it.
TEST_F(UavslamCli, ADoorJambSearchedForFixesTheAxisABiasedImuLoses) {
  const SearchedAndCarried flown = fly_searched_and_carried(dir, "biased_corridor");
  for (std::size_t i = 0; i < flown.searched_flights.size(); ++i) {
    const nlohmann::json& with = flown.searched_flights[i];
    EXPECT_GT(with.at("scans").at("blind_fixed").get<int>(), 0) << "seed " << i + 1;
    EXPECT_LE(with.at("consistency").at("nees_mean").get<double>(), 6.0) << "seed " << i + 1;
  }
  EXPECT_LT(flown.searched, 0.3 * flown.carried)
      << "carried by the IMU alone " << flown.carried << " m";
}

// The same corridor with a bias-free accelerometer (corridor.yaml), where the IMU alone carries the
// axis as well as it ever will: the search must not cost it. Its fixes teach the inertial filter a
// bias from centimetres, so they must keep coming: a jamb's face paired across the floor with the
// take-off's keyframe, flown a metre lower, keeps them coming through the climb (seeds 1-4: 0.130
// m not searched, 0.278 m when the pairs were sought in 3D, 0.043 m now).
TEST_F(UavslamCli, TheSearchCostsNothingWhereTheImuNeedsNoHelp) {
  const SearchedAndCarried flown = fly_searched_and_carried(dir, "corridor");
  EXPECT_LT(flown.searched, flown.carried) << "carried by the IMU alone " << flown.carried << " m";
}

// The plain corridor with a real accelerometer (a bias of 2-3 mg left by its calibration) and the
// autopilot's velocity from optical flow (flow_corridor.yaml): the IMU alone integrates the bias
// along the blind axis into metres; the shipped config fuses the velocity and holds the corridor.
TEST_F(UavslamCli, TheAutopilotsVelocityCarriesTheCorridorThatABiasedImuLoses) {
  const double fused = ate_horizontal(simulate(dir / "uav", "flow_corridor", "config/slam.yaml"));
  const double imu_alone = ate_horizontal(simulate(dir / "imu", "flow_corridor", "config/slam.yaml",
                                                   "--set motion.fuse_velocity=false"));
  EXPECT_LE(fused, 0.15);
  EXPECT_GT(imu_alone, 1.0);
}

// The demo flown three times as fast (agile.yaml): the vehicle tilts up to 20 degrees into its
// accelerations and the level beams strike the floor ahead. The shipped config sets those points
// aside (scan.floor_margin); read as walls, they pull the match and join the map. One flight says
// little; over noise seeds 1 to 4, 0.036 against 0.473 m (16 seeds: 0.035 against 0.406 m,
// monte_carlo.sh; docs/algorithm.md). Measured as found, with the point pairs counted in the
// refinement: the refinement on the lines (icp.refine_lines_only) keeps most strikes out of the
// match too, and seeds 1-4 then no longer show it (16 seeds still do: 0.113 m mean kept, one
// flight 1.15 m off, against 0.009 m). Issue 17's NEES is checked on the shipped config.
TEST_F(UavslamCli, AFastFlightsFloorStrikesAreSetAside) {
  constexpr int kSeeds = 4;
  double set_aside_ate = 0.0;
  double kept_ate = 0.0;
  double shipped_nees = 0.0;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    const std::string options =
        "--seed " + std::to_string(seed) + " --set icp.refine_lines_only=false";
    const fs::path out = dir / ("uav" + std::to_string(seed));
    const nlohmann::json set_aside = simulate(out, "agile", "config/slam.yaml", options);
    const nlohmann::json kept =
        simulate(dir / ("kept" + std::to_string(seed)), "agile", "config/slam.yaml",
                 options + " --set scan.floor_margin=0");
    const nlohmann::json shipped = simulate(dir / ("shipped" + std::to_string(seed)), "agile",
                                            "config/slam.yaml", "--seed " + std::to_string(seed));
    set_aside_ate += ate_horizontal(set_aside) / kSeeds;
    kept_ate += ate_horizontal(kept) / kSeeds;
    shipped_nees += shipped.at("consistency").at("nees_mean").get<double>() / kSeeds;
    // scans.csv counts each scan's floor strikes: hundreds of scans have some.
    std::ifstream csv(out / "scans.csv");
    std::string line;
    std::getline(csv, line);
    ASSERT_NE(line.find(",floor_returns,"), std::string::npos) << line;
    std::size_t striking = 0;
    while (std::getline(csv, line)) {
      const std::vector<std::string> fields = fields_of(line);
      ASSERT_GE(fields.size(), 23u) << line;
      striking += std::stoul(fields[22]) > 0;
    }
    EXPECT_GT(striking, 200u) << seed;
    EXPECT_EQ(set_aside.at("scans").at("floor_strikes").at("scans").get<std::size_t>(), striking);
  }
  EXPECT_LE(set_aside_ate, 0.06);
  EXPECT_GT(kept_ate, 0.2);
  EXPECT_GE(shipped_nees, 1.5);
  EXPECT_LE(shipped_nees, 6.0);
}

// A UTM-30LX sweeps its 270 degrees in 18.75 ms (the scenarios' lidar.sweep_seconds), while the
// agile flight turns at up to 1.1 rad/s and flies at up to 2.8 m/s: a wall seen at both ends of
// the sweep is seen from two places. The shipped config places each beam from where the body was
// when it fired (scan.deskew); over seeds 1-4, 0.009 against 0.025 m left as swept.
TEST_F(UavslamCli, EachBeamIsPlacedFromWhereTheVehicleWasWhenItFired) {
  const double undone = mean_ate(dir / "undone", "agile", "", 4);
  const double swept = mean_ate(dir / "swept", "agile", "--set scan.deskew=false", 4);
  EXPECT_LT(undone, 0.6 * swept) << "left as swept " << swept << " m";
}

// The agile flight's take-off tilts the scanner to 15 degrees: its cut of the room is then not the
// map's, and a heading taken from it walks off by a degree in a second, turning the map built
// meanwhile. Above icp.heading_max_tilt the heading stays the IMU's (seeds 1-4: 0.025 against
// 0.039 m). Measured as found, with the point pairs counted in the refinement: refined on the lines
// (icp.refine_lines_only), the tilted scans' heading no longer walks and the limit costs 2 mm
// (16 seeds: 0.009 m with it, 0.007 m without; docs/algorithm.md).
TEST_F(UavslamCli, ATiltedScannerLeavesTheHeadingToTheImu) {
  const std::string points = "--set icp.refine_lines_only=false";
  const double limited = mean_ate(dir / "limited", "agile", points, 4);
  const double unlimited =
      mean_ate(dir / "unlimited", "agile", points + " --set icp.heading_max_tilt=0", 4);
  EXPECT_LT(limited, 0.8 * unlimited) << "unlimited " << unlimited << " m";
}

// A 60 x 40 m hall (hall.yaml), its walls and pillars seen at 20-30 m: a heading left within a
// periodic check's tolerance (0.01 rad) moves them by 0.2-0.3 m, and the map with them. The
// shipped config takes the heading from every scan (seeds 1-2: 0.086 against 0.236 m).
TEST_F(UavslamCli, AHallsFarWallsTakeTheHeadingFromEveryScan) {
  const double every_scan = mean_ate(dir / "every", "hall", "", 2);
  // The map turned once onto the IMU's heading, by about one sample's noise (0.1 degree).
  std::ifstream json_file(dir / "every" / "seed1" / "summary.json");
  const nlohmann::json anchor = nlohmann::json::parse(json_file).at("heading_anchor");
  EXPECT_LT(std::abs(anchor.at("turn_deg").get<double>()), 0.5);
  EXPECT_GE(anchor.at("after_s").get<double>(), 3.0);
  EXPECT_LT(anchor.at("after_s").get<double>(), 3.1);
  const double checked = mean_ate(dir / "checked", "hall", "--set icp.heading=periodic_check", 2);
  EXPECT_LE(every_scan, 0.15);
  EXPECT_LT(every_scan, 0.6 * checked) << "checked " << checked << " m";
}

// The hall's floor is mostly floor the map has not seen: the height chained from keyframe to
// keyframe walks (0.09 m over 160 s on seed 1). The shipped config takes the floor's level at
// take-off and measures the height from it wherever that floor is seen again.
TEST_F(UavslamCli, TheHallsHeightComesFromTheTakeOffFloorsLevel) {
  const auto vertical = [](const nlohmann::json& summary) {
    return summary.at("trajectory_errors").at("ate_vertical_rmse_m").get<double>();
  };
  const nlohmann::json level = simulate(dir / "level", "hall", "config/slam.yaml");
  const nlohmann::json chained =
      simulate(dir / "chained", "hall", "config/slam.yaml", "--set floor.level_gate=0");
  EXPECT_LE(vertical(level), 0.02);
  EXPECT_GT(vertical(chained), 3.0 * vertical(level)) << "chained " << vertical(chained) << " m";
  const std::size_t accepted = level.at("scans").at("accepted").get<std::size_t>();
  EXPECT_GT(level.at("scans").at("height_from_floor").get<std::size_t>(), accepted / 2)
      << "most scans see the take-off floor";
  EXPECT_EQ(chained.at("scans").at("height_from_floor").get<std::size_t>(), 0u);
}

// The hall flown along its walls: the far walls' map points, every 5th of a scan that meets them
// at a grazing angle, lie too far apart for a wall normal, and counted point to point their
// offsets turned the heading keyframe after keyframe (+2.75 mrad, 8 cm at 30 m). The shipped
// refinement counts them only where the walls with a normal leave the match free.
TEST_F(UavslamCli, TheHallsFarWallPointsNoLongerTurnTheMatch) {
  const double refined = ate_horizontal(simulate(dir / "lines", "hall", "config/slam.yaml"));
  const double counted = ate_horizontal(
      simulate(dir / "points", "hall", "config/slam.yaml", "--set icp.refine_lines_only=false"));
  EXPECT_LE(refined, 0.03);
  EXPECT_GT(counted, 3.0 * refined) << "counted point to point: " << counted << " m";
}

// Every 20th scan taken 0.15 s before its stamp (late_scans.yaml): each such scan matches where
// the vehicle was. The shipped gate on the prior refuses them; without it they pull the pose and
// the map back each time (with the point-to-line match 0.052 m against 0.036 m; 0.196 m with the
// seed's point-to-point, which holds a scan to the map points it was taken beside).
TEST_F(UavslamCli, TheGateOnThePriorRefusesLateScans) {
  const nlohmann::json gated = simulate(dir / "uav", "late_scans", "config/slam.yaml");
  const nlohmann::json ungated =
      simulate(dir / "open", "late_scans", "config/slam.yaml", "--set icp.prior_gate=0");
  EXPECT_LE(ate_horizontal(gated), 0.10);
  EXPECT_GT(ate_horizontal(ungated), 1.3 * ate_horizontal(gated));
  EXPECT_GT(gated.at("scans").at("rejected_by_reason").at("disagrees_with_prior").get<int>(), 100)
      << "of 360 late scans";
}

// An IMU whose yaw drifts 2 degrees a minute (yaw_drift.yaml): the shipped UAV config estimates
// the heading against the map in every scan (icp.heading every_scan) and keeps the map straight;
// the seed's heading, the IMU's as it is, bends it.
TEST_F(UavslamCli, TheShippedConfigCorrectsTheImusYawDrift) {
  // The front end's heading check alone: the back end, which would also straighten the map, off.
  const std::string no_loops = "--set loop_closure.enabled=false";
  const double checked =
      ate_horizontal(simulate(dir / "uav", "yaw_drift", "config/slam.yaml", no_loops));
  const double trusted = ate_horizontal(simulate(dir / "source", "yaw_drift", "config/slam.yaml",
                                                 no_loops + " --set icp.heading=source"));
  EXPECT_LE(checked, 0.25);
  EXPECT_GT(trusted, 0.3);
}

// The same drift seen by periodic heading checks against old map (icp.heading periodic_check,
// the UAV's default before the heading came from every scan): they learn it (2 degrees a minute,
// the scenario's) and turn the heading back as it goes, so the keyframes stop joining the map
// turned by it. Without (imu.heading_drift_sigma 0) a check against the last
// keyframes sees only the drift since they were made, under its tolerance, and the map turns. One
// flight says little (seed 1: 0.173 m followed against 0.103 m not, the front end alone); over
// noise seeds 1 to 4, 0.107 against 0.131 m (8 seeds: 0.095 against 0.130 m, monte_carlo.sh).
TEST_F(UavslamCli, TheHeadingChecksLearnTheImusDriftAndFollowIt) {
  const std::string no_loops = "--set loop_closure.enabled=false --set icp.heading=periodic_check";
  constexpr int kSeeds = 4;
  double followed_ate = 0.0;
  double unfollowed_ate = 0.0;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    const std::string options = no_loops + " --seed " + std::to_string(seed);
    const nlohmann::json followed =
        simulate(dir / ("uav" + std::to_string(seed)), "yaw_drift", "config/slam.yaml", options);
    const nlohmann::json unfollowed =
        simulate(dir / ("still" + std::to_string(seed)), "yaw_drift", "config/slam.yaml",
                 options + " --set imu.heading_drift_sigma=0");
    EXPECT_NEAR(followed.at("heading_drift_deg_per_min").get<double>(), 2.0, 0.2) << seed;
    EXPECT_EQ(unfollowed.at("heading_drift_deg_per_min").get<double>(), 0.0) << seed;
    followed_ate += ate_horizontal(followed) / kSeeds;
    unfollowed_ate += ate_horizontal(unfollowed) / kSeeds;
  }
  EXPECT_LT(followed_ate, 0.9 * unfollowed_ate);
  // A steady IMU (demo.yaml): nothing to learn, nothing followed.
  const nlohmann::json steady = simulate(dir / "demo", "demo", "config/slam.yaml", no_loops);
  EXPECT_EQ(steady.at("heading_drift_deg_per_min").get<double>(), 0.0);
}

// The same drifting IMU with the back end on: the flight comes back through the rooms it mapped,
// the loops found there are optimised into the keyframe graph, and the map and the pose move with
// it; once the heading checks have learnt the drift, the keyframes made before it turn by it too.
// What the vehicle flew on beats the front end alone (horizontal 0.058 against 0.173 m with the
// default noise seed; before the keyframes were turned and the robust refinement, 0.095 against
// 0.097 m), the final graph's poses by more than half (0.065 against 0.186 m).
TEST_F(UavslamCli, TheBackEndClosesTheLoopsOfAFlightWhoseImuDrifts) {
  // The heading checked periodically: taken from every scan (the shipped mode), the drift no
  // longer bends the map and the loops have nothing to straighten. The point pairs counted in
  // the refinement, as when this was measured: refined on the lines, the front end alone is
  // within 0.053 m and the loops no longer improve on it by a fifth.
  const std::string checked = "--set icp.heading=periodic_check --set icp.refine_lines_only=false";
  const nlohmann::json alone = simulate(dir / "alone", "yaw_drift", "config/slam.yaml",
                                        checked + " --set loop_closure.enabled=false");
  const nlohmann::json closed = simulate(dir / "closed", "yaw_drift", "config/slam.yaml", checked);
  EXPECT_GT(closed.at("loops").at("accepted").get<int>(), 10);
  EXPECT_EQ(closed.at("loops").at("rejected_by_graph").get<int>(), 0);
  EXPECT_FALSE(alone.contains("loops"));
  const double after = closed.at("trajectory_errors_after_loops").at("ate_rmse_m").get<double>();
  EXPECT_LT(ate_horizontal(closed), 0.8 * ate_horizontal(alone));
  EXPECT_LT(after, 0.7 * alone.at("trajectory_errors").at("ate_rmse_m").get<double>());
}

// Out through a door, around another room and back (two_rooms.yaml, the IMU's heading
// drifting): coming back, the first room's map is where the drift left it. The back end turns
// the keyframes made before the drift was learnt and finds the loop there; the final graph puts
// the flight back where it was (0.141 -> 0.055 m; 0.130 m as flown with the loop).
TEST_F(UavslamCli, TheBackEndClosesTheLoopThroughTheOtherRoom) {
  // The heading checked periodically, as in the test above (with the shipped heading from every
  // scan the flight comes back where it left: 0.016 m over 16 seeds, the loops moving nothing).
  const std::string checked = "--set icp.heading=periodic_check";
  const nlohmann::json alone = simulate(dir / "alone", "two_rooms", "config/slam.yaml",
                                        checked + " --set loop_closure.enabled=false");
  const nlohmann::json closed = simulate(dir / "closed", "two_rooms", "config/slam.yaml", checked);
  EXPECT_GT(closed.at("loops").at("accepted").get<int>(), 0);
  const double before = alone.at("trajectory_errors").at("ate_rmse_m").get<double>();
  const double after = closed.at("trajectory_errors_after_loops").at("ate_rmse_m").get<double>();
  EXPECT_LT(after, 0.6 * before) << "before " << before << " m";
}

// The 60 m corridor there and back (corridor.yaml) with the noise of seed 11: along the axis the
// scans are blind for most of the way out, and the IMU's prior carried the vehicle short of where
// it was (2.4 m; 1.2 m before the robust refinement, 7.6 m while the inertial filter took the
// matches for surer than they are, after loops 0.21 m now); the
// map it made there is as wrong, and the scans agree with it all the way back. Only the take-off's
// map, at the end wall, says otherwise. The graph's steps are as unsure along the axis as the
// prior grew, so the loop back there is searched that far and the final graph keeps it.
TEST_F(UavslamCli, TheBackEndFindsTheLoopABlindCorridorHid) {
  // The heading checked periodically, the height chained and the point pairs counted in the
  // refinement, as when this seed was found: with the heading from every scan the same seed is
  // lost the other way, by 8.6 m, and with the height from the floor's level too, by 10.9 m,
  // beyond the loop search's max_radius; refined on the lines it is not lost (0.20 m). Every
  // beam at the stamp, as then: with the scanner's sweep it is not lost either (0.24 m). The
  // blind axis not searched, as then: a door jamb searched for fixes it (0.12 m). The matches'
  // errors independent in the inertial filter, as then: with their shared part a state of its
  // own, this flight is lost by 4.1 m, beyond the loop search's 3 m (loop_closure.max_radius).
  const nlohmann::json closed =
      simulate(dir / "c", without_sweep("corridor", dir), "config/slam.yaml",
               "--seed 11 --set icp.heading=periodic_check --set "
               "floor.level_gate=0 --set icp.refine_lines_only=false --set "
               "degeneracy.search_window=0 --set motion.match_error_sigma=0");
  EXPECT_GE(closed.at("loops").at("accepted").get<int>(), 1);
  const double flown = closed.at("trajectory_errors").at("ate_rmse_m").get<double>();
  const double after = closed.at("trajectory_errors_after_loops").at("ate_rmse_m").get<double>();
  EXPECT_GT(flown, 1.0) << "the flight must have lost the axis for the test to mean anything";
  EXPECT_LT(after, 0.4 * flown) << "as flown " << flown << " m";
}

// --seed: the same flight with other sensor noise (Monte Carlo runs); the same seed, the same run.
TEST_F(UavslamCli, TheSeedOptionRepeatsAFlightWithOtherNoise) {
  const auto estimate = [&](const std::string& seed, const std::string& name) {
    const fs::path out = dir / name;
    const CommandResult r =
        run("simulate --quiet --scenario " + source("config/scenarios/short.yaml") + " --config " +
            source("config/slam.yaml") + " --seed " + seed + " --out " + out.string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    std::ifstream file(out / "estimate.tum");
    return std::string(std::istreambuf_iterator<char>(file), {});
  };
  const std::string first = estimate("5", "a");
  ASSERT_FALSE(first.empty());
  EXPECT_EQ(estimate("5", "b"), first);
  EXPECT_NE(estimate("6", "c"), first);
  const CommandResult bad = run("simulate --scenario " + source("config/scenarios/short.yaml") +
                                " --seed minus --out " + (dir / "d").string());
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_THAT(bad.output, HasSubstr("--seed"));
}

TEST_F(UavslamCli, HelpListsTheCommands) {
  const CommandResult r = run("--help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("simulate"));
  EXPECT_THAT(r.output, HasSubstr("eval"));
  EXPECT_THAT(r.output, HasSubstr("sweep"));
}

TEST_F(UavslamCli, AMissingScenarioFileIsNamed) {
  const CommandResult r = run("simulate --scenario /nonexistent/flight.yaml --out " + dir.string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("/nonexistent/flight.yaml"));
}

TEST_F(UavslamCli, AnIllTypedScenarioKeyNamesFileKeyAndValue) {
  const std::string path = write("bad.yaml",
                                 "world:\n  room: {min: [0, 0, 0], max: [20, 15, 4]}\n"
                                 "trajectory:\n  waypoints:\n"
                                 "    - {t: 0, position: [2, 2, 1], yaw_deg: 0}\n"
                                 "    - {t: 5, position: [4, 2, 1], yaw_deg: 0}\n"
                                 "lidar: {rate_hz: fast}\n");
  const CommandResult r = run("simulate --scenario " + path + " --out " + (dir / "o").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr(path));
  EXPECT_THAT(r.output, HasSubstr("lidar.rate_hz"));
  EXPECT_THAT(r.output, HasSubstr("fast"));
}

TEST_F(UavslamCli, AMissingRequiredScenarioKeyIsNamed) {
  const std::string path = write("noroom.yaml",
                                 "trajectory:\n  waypoints:\n"
                                 "    - {t: 0, position: [2, 2, 1]}\n"
                                 "    - {t: 5, position: [4, 2, 1]}\n");
  const CommandResult r = run("simulate --scenario " + path + " --out " + (dir / "o").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("world"));
}

TEST_F(UavslamCli, AnUnknownConfigKeyOrOverrideIsRefused) {
  const std::string config = write("slam.yaml", "icp:\n  iteratons: 12\n");
  const std::string scenario = source("config/scenarios/short.yaml");
  const CommandResult r = run("simulate --scenario " + scenario + " --config " + config +
                              " --out " + (dir / "o").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("icp.iteratons"));

  const CommandResult s = run("simulate --scenario " + scenario + " --set icp.iterations=many" +
                              " --out " + (dir / "o").string());
  EXPECT_EQ(s.exit_code, 2) << s.output;
  EXPECT_THAT(s.output, HasSubstr("many"));
}

TEST_F(UavslamCli, EvalNamesTheLineOfAMalformedTrajectory) {
  const std::string good = write("gt.tum", "0 0 0 0 0 0 0 1\n1 1 0 0 0 0 0 1\n");
  const std::string bad = write("est.tum", "0 0 0 0 0 0 0 1\n1 1 0 0 0\n");
  const CommandResult r = run("eval --estimate " + bad + " --groundtruth " + good);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr(bad + ":2:"));
}

// The launcher on plain programs (no DDS): the run ends with the until_exit process; a process
// that ends cleanly before it leaves the others running; a failing one stops the run.
TEST_F(UavslamCli, LaunchRunsUntilTheUntilExitProcessEnds) {
  const std::string file = write("launch.yaml", "log_dir: " + (dir / "logs").string() + R"(
processes:
  - {name: quick, executable: /bin/true, node_options: false}
  - {name: sleeper, executable: /bin/sleep, args: ["0.5"], node_options: false, until_exit: true}
)");
  const CommandResult result = run("launch " + file);
  EXPECT_EQ(result.exit_code, 0) << result.output;
  const std::string ended = "launch: quick ended (exit 0)";
  const std::size_t first = result.output.find(ended);
  ASSERT_NE(first, std::string::npos) << result.output;
  EXPECT_EQ(result.output.find(ended, first + 1), std::string::npos) << "announced once";
  EXPECT_THAT(result.output, HasSubstr("launch: sleeper ended (exit 0)"));
  EXPECT_TRUE(fs::exists(dir / "logs" / "sleeper.log"));
}

TEST_F(UavslamCli, LaunchStopsEverythingWhenAProcessFails) {
  const std::string file = write("launch.yaml", "log_dir: " + (dir / "logs").string() + R"(
stop_grace_s: 5
processes:
  - {name: sleeper, executable: /bin/sleep, args: ["60"], node_options: false, until_exit: true}
  - {name: broken, executable: /bin/false, node_options: false}
)");
  const CommandResult result = run("launch " + file);
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_THAT(result.output, HasSubstr("launch: broken ended (exit 1)"));
  // SIGINT ended the sleeper: 128 + 2.
  EXPECT_THAT(result.output, HasSubstr("launch: sleeper exit 130"));
}

TEST_F(UavslamCli, LaunchNamesAMissingExecutable) {
  const std::string file =
      write("launch.yaml", "log_dir: " + (dir / "logs").string() + "\nprocesses: [{name: nope}]\n");
  const CommandResult result = run("launch " + file);
  EXPECT_NE(result.exit_code, 0);
  EXPECT_THAT(result.output, HasSubstr("no executable 'nope'"));
}

}  // namespace

// The Freiburg benchmark metric from the command line: one exact short relation and one long one
// 1 m off give 0.5 ± 0.5 m over all relations and 0 under 5 s.
TEST_F(UavslamCli, EvalScoresAPlanarEstimateAgainstRelations) {
  const std::string relations =
      write("r.relations", "100.5 101.5 1 0 0 0 0 0\n100.5 200.25 3 0 0 0 0 0.1\n");
  const std::string estimate = write("est.txt", "200.25 4 0 0\n100.5 0 0 0\n101.5 1 0 0\n");
  const CommandResult r = run("eval --relations " + relations + " --estimate " + estimate);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("0.5000 ± 0.5000 m"));
  EXPECT_THAT(r.output, HasSubstr("over 2 of 2 relations, 0 unmatched"));
  EXPECT_THAT(r.output, HasSubstr("0.0000 ± 0.0000 m"));

  const CommandResult j = run("eval --json --relations " + relations + " --estimate " + estimate);
  ASSERT_EQ(j.exit_code, 0) << j.output;
  const nlohmann::json figures = nlohmann::json::parse(j.output);
  EXPECT_NEAR(figures["all"]["translation_m"]["mean"].get<double>(), 0.5, 1e-9);
  EXPECT_NEAR(figures["all"]["rotation_deg"]["max"].get<double>(), 5.729577951, 1e-6);
  EXPECT_EQ(figures["short_span"]["relations"].get<int>(), 1);

  // Each relation's errors, in the relations' order, for finding where an estimate goes wrong.
  const std::string listing = (dir / "each.csv").string();
  const CommandResult p = run("eval --relations " + relations + " --estimate " + estimate +
                              " --per-relation " + listing);
  ASSERT_EQ(p.exit_code, 0) << p.output;
  std::ifstream each(listing);
  std::vector<std::string> lines;
  for (std::string line; std::getline(each, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0], "t1,t2,span_s,translation_m,rotation_deg,relation_m,along_m,across_m");
  EXPECT_EQ(lines[1], "100.500000,101.500000,1.000000,0,0,1,0,0");
  EXPECT_THAT(lines[2], ::testing::StartsWith("100.500000,200.250000,99.750000,1,5.72957795"));
  // 4 m estimated where the relation says 3: 1 m too far along it, nothing across.
  EXPECT_THAT(lines[2], ::testing::EndsWith(",3,1,0"));
  const CommandResult per_without = run("eval --estimate " + estimate + " --groundtruth " +
                                        estimate + " --per-relation " + listing);
  EXPECT_EQ(per_without.exit_code, 2) << per_without.output;
  EXPECT_THAT(per_without.output, HasSubstr("--per-relation"));

  const std::string bad = write("bad.txt", "100.5 0 0 0\n101.5 1 0\n");
  const CommandResult b = run("eval --relations " + relations + " --estimate " + bad);
  EXPECT_EQ(b.exit_code, 2) << b.output;
  EXPECT_THAT(b.output, HasSubstr(bad + ":2:"));

  const CommandResult both = run("eval --relations " + relations + " --groundtruth " + estimate +
                                 " --estimate " + estimate);
  EXPECT_NE(both.exit_code, 0) << both.output;
  const CommandResult neither = run("eval --estimate " + estimate);
  EXPECT_NE(neither.exit_code, 0) << neither.output;
  const CommandResult no_estimate = run("eval --relations " + relations);
  EXPECT_EQ(no_estimate.exit_code, 2) << no_estimate.output;
  EXPECT_THAT(no_estimate.output, HasSubstr("--estimate is required"));
}

// The relations against themselves: a triangle of scans 0.1 m from closing.
TEST_F(UavslamCli, EvalConsistencyMeasuresTheRelationsTriangles) {
  const std::string relations = write("t.relations",
                                      "1.0 2.0 1 0 0 0 0 0\n2.0 3.0 1 0 0 0 0 0\n"
                                      "1.0 3.0 2.1 0 0 0 0 0\n");
  const CommandResult r = run("eval --consistency --relations " + relations);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("triangles         1 close to within 0.1000"));
  const CommandResult j = run("eval --consistency --json --relations " + relations);
  ASSERT_EQ(j.exit_code, 0) << j.output;
  EXPECT_EQ(nlohmann::json::parse(j.output)["triangles"].get<int>(), 1);
  const CommandResult alone = run("eval --consistency --groundtruth " + relations);
  EXPECT_EQ(alone.exit_code, 2) << alone.output;
}

namespace {

// A FLASER line of a robot at (x, y, theta) in an 8 m x 8 m room centred on the origin: 180
// beams, -90 deg + i * 1 deg, each the distance to the nearest wall.
std::string square_room_flaser(double x, double y, double theta, double stamp) {
  constexpr double kHalfSide = 4.0;
  constexpr double kDegree = 0.017453292519943295;
  std::ostringstream line;
  line << std::fixed << std::setprecision(3) << "FLASER 180";
  for (int i = 0; i < 180; ++i) {
    const double angle = theta + (i - 90) * kDegree;
    const double dx = std::cos(angle);
    const double dy = std::sin(angle);
    double range = 1e9;
    if (std::abs(dx) > 1e-9) range = std::min(range, ((dx > 0 ? kHalfSide : -kHalfSide) - x) / dx);
    if (std::abs(dy) > 1e-9) range = std::min(range, ((dy > 0 ? kHalfSide : -kHalfSide) - y) / dy);
    line << ' ' << range;
  }
  line << std::setprecision(6) << ' ' << x << ' ' << y << ' ' << theta << ' ' << x << ' ' << y
       << ' ' << theta << ' ' << stamp << " robot " << stamp << '\n';
  return line.str();
}

std::vector<double> first_column(const fs::path& path) {
  std::vector<double> values;
  std::ifstream in(path);
  std::string text;
  while (std::getline(in, text)) values.push_back(std::stod(text));
  return values;
}

}  // namespace

// A robot driving across a square room: every scan is tracked, the estimate keeps each scan's own
// timestamp in file order (one runs backwards, as in intel.clf) and a malformed line is counted.
TEST_F(UavslamCli, RunTracksACarmenLogInFileOrder) {
  const std::vector<double> stamps = {100.0, 100.1, 100.2, 100.15, 100.3, 100.4};
  std::string log = "# a synthetic CARMEN log\nPARAM robot_name test\n";
  for (std::size_t i = 0; i < stamps.size(); ++i) {
    log += square_room_flaser(-1.0 + 0.1 * static_cast<double>(i), 0.5,
                              0.02 * static_cast<double>(i), stamps[i]);
    if (i == 2) log += "FLASER 3 1.0 2.0\n";
  }
  const std::string path = write("room.clf", log);
  const fs::path out = dir / "out";
  const CommandResult r = run("run --quiet --carmen " + path + " --out " + out.string() +
                              " --config " + source("config/slam_2d_logs.yaml"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream json(out / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(json);
  EXPECT_EQ(summary["malformed_lines"].get<int>(), 1);
  EXPECT_EQ(summary["scans"]["in"].get<std::size_t>(), stamps.size());
  EXPECT_EQ(summary["scans"]["accepted"].get<std::size_t>(), stamps.size()) << r.output;
  EXPECT_EQ(first_column(out / "estimate.txt"), stamps);
  EXPECT_EQ(uavslam::io::read_tum((out / "estimate.tum").string()).size(), stamps.size());
  EXPECT_FALSE(uavslam::io::read_ply((out / "map.ply").string()).empty());
}

// A newcomer's `uavslam run --carmen LOG` with no --config gets the configuration made for real
// 2D logs (odometry prior, yaw in every scan, the back end), and the seed's mode is one flag away.
TEST_F(UavslamCli, RunWithoutAConfigUsesTheRealLogsConfig) {
  std::string log;
  for (int i = 0; i < 6; ++i)
    log += square_room_flaser(-1.0 + 0.1 * i, 0.5, 0.02 * i, 100.0 + 0.1 * i);
  const std::string path = write("room.clf", log);
  const CommandResult plain = run("run --carmen " + path + " --out " + (dir / "plain").string());
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  EXPECT_THAT(plain.output, HasSubstr("config/slam_2d_logs.yaml (the default for 2D logs"));
  std::ifstream plain_json(dir / "plain" / "summary.json");
  EXPECT_TRUE(nlohmann::json::parse(plain_json).contains("loops")) << "the back end is on";
  const CommandResult seed = run("run --quiet --carmen " + path + " --config " +
                                 source("config/seed.yaml") + " --out " + (dir / "seed").string());
  ASSERT_EQ(seed.exit_code, 0) << seed.output;
  std::ifstream seed_json(dir / "seed" / "summary.json");
  EXPECT_FALSE(nlohmann::json::parse(seed_json).contains("loops"));
}

// The scans' own alignment of each relation: an exact relation scores 0, one 0.1 m off scores
// 0.1 m (the scans show the true motion), one naming a scan the log lacks is unmatched.
TEST_F(UavslamCli, EvalScansScoresTheRelationsAgainstTheScansOwnAlignment) {
  std::string log;
  for (int i = 0; i < 3; ++i) {
    log += square_room_flaser(-1.0 + 0.2 * i, 0.5, 0.02 * i, 100.0 + 0.1 * i);
  }
  const std::string path = write("room.clf", log);
  const double c = std::cos(0.02);
  const double s = std::sin(0.02);
  std::ostringstream relations;
  relations << std::fixed << std::setprecision(6) << "100.0 100.1 0.2 0 0 0 0 0.02\n"
            << "100.1 100.2 " << 0.2 * c + 0.1 << ' ' << -0.2 * s << " 0 0 0 0.02\n"
            << "100.0 107.0 1 0 0 0 0 0\n";
  const std::string relations_path = write("room.relations", relations.str());
  const std::string config = " --config " + source("config/slam_2d_logs.yaml");
  const CommandResult r =
      run("eval --json --relations " + relations_path + " --scans " + path + config);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json figures = nlohmann::json::parse(r.output);
  EXPECT_EQ(figures["relations_without_their_scans"].get<int>(), 1);
  EXPECT_EQ(figures["all"]["unmatched"].get<int>(), 1);
  EXPECT_NEAR(figures["all"]["translation_m"]["max"].get<double>(), 0.1, 2e-3);
  EXPECT_NEAR(figures["all"]["translation_m"]["mean"].get<double>(), 0.05, 2e-3);

  const CommandResult text =
      run("eval --relations " + relations_path + " --scans " + path + config);
  EXPECT_EQ(text.exit_code, 0) << text.output;
  EXPECT_THAT(text.output, HasSubstr("over 2 of 3 relations, 1 unmatched"));
  // Each relation's own figure, to set beside an estimate's (--per-relation with --estimate).
  const std::string listing = (dir / "scans.csv").string();
  const CommandResult each = run("eval --relations " + relations_path + " --scans " + path +
                                 config + " --per-relation " + listing);
  ASSERT_EQ(each.exit_code, 0) << each.output;
  std::ifstream listed(listing);
  std::vector<std::string> lines;
  for (std::string line; std::getline(listed, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_THAT(lines[1], ::testing::StartsWith("100.000000,100.100000,0.100000,"));
  // The unmatched relation: its length (1 m), no errors.
  EXPECT_EQ(lines[3], "100.000000,107.000000,7.000000,,,1,,") << "the unmatched relation";
  const CommandResult with_estimate =
      run("eval --relations " + relations_path + " --scans " + path + " --estimate " + path);
  EXPECT_EQ(with_estimate.exit_code, 2) << with_estimate.output;
  const CommandResult alone = run("eval --groundtruth " + relations_path + " --scans " + path);
  EXPECT_EQ(alone.exit_code, 2) << alone.output;
}

// The smaller Freiburg log end to end with the shipped config: the run completes, most scans are
// matched, every relation finds its poses, and estimating yaw in every scan beats the odometry it
// starts from by far (odometry alone: 6.5 m / 0.059 m / 2.4 deg). The bounds leave room for the
// spread docs/real-logs.md reports under tiny perturbations (0.03-0.18 m over all relations).
TEST_F(UavslamCli, RunCoversTheFr079Log) {
  if (!fs::exists(kFreiburg / "fr079.clf")) GTEST_SKIP() << "no Freiburg data at " << kFreiburg;
  const std::optional<RealLogRun> fr079 = run_real_log("fr079", dir / "fr079");
  ASSERT_TRUE(fr079);
  const nlohmann::json& summary = fr079->summary;
  EXPECT_GT(summary["scans"]["accepted"].get<double>(), 0.9 * summary["scans"]["in"].get<double>());
  const nlohmann::json& figures = fr079->relations;
  EXPECT_EQ(figures["all"]["unmatched"].get<int>(), 0) << "a dead-reckoned pose for every scan";
  EXPECT_LT(figures["all"]["translation_m"]["mean"].get<double>(), 0.5);
  EXPECT_LT(figures["short_span"]["translation_m"]["mean"].get<double>(), 0.04);
  EXPECT_LT(figures["short_span"]["rotation_deg"]["mean"].get<double>(), 1.0);
}

// ACES, a building the front end was not developed on: its long corridors drift, and the shipped
// 2D-logs configuration closes the loops (the back end): all relations 0.122 m without it.
TEST_F(UavslamCli, RunClosesTheLoopsOfTheAcesLog) {
  if (!fs::exists(kFreiburg / "aces.clf")) GTEST_SKIP() << "no Freiburg data at " << kFreiburg;
  const std::optional<RealLogRun> aces = run_real_log("aces", dir / "aces");
  ASSERT_TRUE(aces);
  EXPECT_THAT(aces->output, HasSubstr("  loops             "));
  EXPECT_GT(aces->summary["loops"]["accepted"].get<int>(), 5);
  const nlohmann::json& figures = aces->relations;
  EXPECT_EQ(figures["all"]["unmatched"].get<int>(), 0);
  EXPECT_LT(figures["all"]["translation_m"]["mean"].get<double>(), 0.06);
}

// The scans' own alignment on both Freiburg logs: every relation names scans the log has (the
// stamps are looked up exactly), and nearly every short relation's two scans align.
TEST_F(UavslamCli, EvalScansFindsEveryRelationsScansInTheFreiburgLogs) {
  const fs::path& data = kFreiburg;
  if (!fs::exists(data / "fr079.clf")) GTEST_SKIP() << "no Freiburg data at " << data;
  for (const std::string log : {"intel", "fr079"}) {
    const CommandResult r =
        run("eval --json --relations " + (data / (log + ".relations")).string() + " --scans " +
            (data / (log + ".clf")).string() + " --config " + source("config/slam_2d_logs.yaml"));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const nlohmann::json figures = nlohmann::json::parse(r.output);
    EXPECT_EQ(figures["relations_without_their_scans"].get<int>(), 0) << log;
    const nlohmann::json& short_span = figures["short_span"];
    EXPECT_LT(short_span["unmatched"].get<double>(), 0.05 * short_span["relations"].get<double>())
        << log;
  }
}

// The offline dense mapper on the short flight: every output is written and reads back, the dense
// pass (every point, exact search) is at least as accurate as the real-time pass, and the cloud
// lies on the simulated world's surfaces. The seed's matcher (point-to-point), whose offline
// variant this is; with the shipped point-to-line the dense pass is better locally (RPE 0.014
// against 0.015 m) but not over the flight (ATE 0.025 against 0.023 m, docs/algorithm.md).
TEST_F(UavslamCli, OfflineMapsTheShortFlightDenselyAndComparesItWithRealTime) {
  const fs::path out = dir / "offline";
  const CommandResult r =
      run("offline --quiet --scenario " + source("config/scenarios/short.yaml") + " --config " +
          source("config/slam.yaml") + " --set icp.metric=point_to_point --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream json(out / "report.json");
  const nlohmann::json report = nlohmann::json::parse(json);
  const nlohmann::json& offline = report.at("offline");
  const nlohmann::json& realtime = report.at("realtime");
  EXPECT_EQ(offline.at("scans").get<std::size_t>(), 801u);
  EXPECT_EQ(realtime.at("scans").get<std::size_t>(), 801u);
  const double offline_ate = offline.at("errors").at("ate_rmse_m").get<double>();
  const double realtime_ate = realtime.at("errors").at("ate_rmse_m").get<double>();
  EXPECT_LE(offline_ate, realtime_ate) << r.output;
  const nlohmann::json& cloud = offline.at("cloud");
  EXPECT_LT(cloud.at("distance_to_true_surfaces").at("mean_m").get<double>(), 0.03) << r.output;
  EXPECT_GT(cloud.at("points_before_voxel_filter").get<std::size_t>(),
            cloud.at("points").get<std::size_t>());
  EXPECT_TRUE(report.contains("trajectory_difference"));

  const std::vector<uavslam::DensePoint> pcd = uavslam::io::read_pcd((out / "cloud.pcd").string());
  EXPECT_EQ(pcd.size(), cloud.at("points").get<std::size_t>());
  EXPECT_EQ(uavslam::io::read_ply((out / "cloud.ply").string()).size(), pcd.size());
  const auto tree = uavslam::io::read_bt((out / "map.bt").string());
  EXPECT_EQ(uavslam::io::occupied_cell_centres(*tree).size(),
            cloud.at("octomap_occupied_leaves").get<std::size_t>());
  EXPECT_EQ(uavslam::io::read_tum((out / "estimate.tum").string()).size(),
            offline.at("posed").get<std::size_t>());
  EXPECT_FALSE(fs::exists(out / "estimate.txt")) << "estimate.txt is for CARMEN logs";
}

// On a CARMEN log whose config already matches every point with the exact index (the 2D logs'
// config), the offline pass is the real-time pass: the same estimate.txt as `uavslam run`.
TEST_F(UavslamCli, OfflineOnACarmenLogAgreesWithRun) {
  std::string log;
  for (int i = 0; i < 8; ++i) {
    log += square_room_flaser(-1.0 + 0.1 * i, 0.5, 0.02 * i, 100.0 + 0.1 * i);
  }
  const std::string path = write("room.clf", log);
  const std::string config = " --config " + source("config/slam_2d_logs.yaml");
  const CommandResult offline =
      run("offline --carmen " + path + config + " --out " + (dir / "offline").string());
  ASSERT_EQ(offline.exit_code, 0) << offline.output;
  // Not a terminal: plain progress lines, the last at 100 %.
  EXPECT_THAT(offline.output, HasSubstr("100% 8/8 scans")) << offline.output;
  const CommandResult online =
      run("run --quiet --carmen " + path + config + " --out " + (dir / "run").string());
  ASSERT_EQ(online.exit_code, 0) << online.output;
  std::ifstream a(dir / "offline" / "estimate.txt"), b(dir / "run" / "estimate.txt");
  const std::string offline_estimate{std::istreambuf_iterator<char>(a), {}};
  const std::string run_estimate{std::istreambuf_iterator<char>(b), {}};
  EXPECT_FALSE(offline_estimate.empty());
  EXPECT_EQ(offline_estimate, run_estimate);
  EXPECT_FALSE(uavslam::io::read_pcd((dir / "offline" / "cloud.pcd").string()).empty());
}

// A ground building of config/scenarios/ground written by `uavslam simulate --carmen` into dir:
// its CARMEN log and its relations.
struct GroundLog {
  std::string log, relations;
};
GroundLog simulate_ground(const fs::path& dir, const std::string& building,
                          const std::string& options = "") {
  const GroundLog ground{(dir / (building + ".clf")).string(),
                         (dir / (building + ".relations")).string()};
  simulate(dir / "sim", source("config/scenarios/ground/" + building + ".yaml"), "config/seed.yaml",
           options + " --carmen " + ground.log);
  EXPECT_TRUE(fs::exists(ground.relations)) << ground.relations;
  return ground;
}

// The relation error of `uavslam run --carmen` on a ground log [options]
// (config/slam_2d_logs.yaml) against its relations, over all relations: mean and largest (m); the
// run's summary.json.
struct ScoredRun {
  double mean = 0.0, max = 0.0;
  nlohmann::json summary;
};
ScoredRun run_and_score(const GroundLog& ground, const fs::path& out,
                        const std::string& options = "") {
  const CommandResult r =
      run("run --quiet --carmen " + ground.log + " --config " + source("config/slam_2d_logs.yaml") +
          " " + options + " --out " + out.string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  const CommandResult e = run("eval --json --relations " + ground.relations + " --estimate " +
                              (out / "estimate.txt").string());
  EXPECT_EQ(e.exit_code, 0) << e.output;
  const nlohmann::json scores = nlohmann::json::parse(e.output);
  std::ifstream summary(out / "summary.json");
  return {scores["all"]["translation_m"]["mean"], scores["all"]["translation_m"]["max"],
          nlohmann::json::parse(summary)};
}

// A ground robot once round a ring corridor (config/scenarios/ground/ring_corridor.yaml), written
// as a CARMEN log by `simulate --carmen`: back at its start, the loop search finds the corridor's
// outer walls lying on the central block's faces (3.5 m off across both corridors, scoring above
// min_score), seen from the block's inside. Taken, that loop moved the map by 5 m.
TEST_F(UavslamCli, ALoopThatLaysAWallOnTheFarSideOfABlockIsRefused) {
  const GroundLog ring = simulate_ground(dir, "ring_corridor");

  const ScoredRun checked = run_and_score(ring, dir / "checked");
  EXPECT_GE(checked.summary["loops"]["rejected_back_to_back"].get<int>(), 1);
  EXPECT_GE(checked.summary["loops"]["accepted"].get<int>(), 1);
  EXPECT_LT(checked.mean, 0.03);
  EXPECT_LT(checked.max, 0.5);

  const ScoredRun unchecked =
      run_and_score(ring, dir / "unchecked", "--set loop_closure.max_opposed_share=1");
  EXPECT_EQ(unchecked.summary["loops"]["rejected_back_to_back"].get<int>(), 0);
  EXPECT_GT(unchecked.max, 1.0);
}

// Down a corridor of niches and back (config/scenarios/ground/long_corridor.yaml): the way back
// sees each niche's other face, and the loop search slides one face onto the other, 1 m along
// the corridor, where the walls cannot tell. Taken, such loops bent the map by 2.4 m.
TEST_F(UavslamCli, ALoopThatSlidesANichesFaceOntoItsOtherFaceIsRefused) {
  const GroundLog corridor = simulate_ground(dir, "long_corridor");

  const ScoredRun checked = run_and_score(corridor, dir / "checked");
  EXPECT_GE(checked.summary["loops"]["rejected_back_to_back"].get<int>(), 1);
  EXPECT_LT(checked.mean, 0.02);
  EXPECT_LT(checked.max, 0.5);

  const ScoredRun unchecked =
      run_and_score(corridor, dir / "unchecked", "--set loop_closure.max_opposed_share=1");
  EXPECT_GT(unchecked.max, 1.0);
}

// Into a round hall and a turn on the spot off its centre (config/scenarios/ground/round_hall.yaml,
// noise seed 6): a turn about the hall's centre and a shift are one to the scans, and the ICP's
// yaw slid 115 degrees off in that seed. Held at the odometry's where the scan cannot see it.
TEST_F(UavslamCli, AYawTheScanCannotSeeIsHeldAtTheOdometrys) {
  const GroundLog hall = simulate_ground(dir, "round_hall", "--seed 6");

  const ScoredRun held = run_and_score(hall, dir / "held");
  EXPECT_GT(held.summary["scans"]["yaw_held"].get<int>(), 0);
  EXPECT_LT(held.mean, 0.02);
  EXPECT_LT(held.max, 0.5);

  const ScoredRun slid = run_and_score(hall, dir / "slid", "--set degeneracy.hold_blind_yaw=false");
  EXPECT_EQ(slid.summary["scans"]["yaw_held"].get<int>(), 0);
  EXPECT_GT(slid.max, 1.0);
}

// Round the ring corridor among eight people (config/scenarios/ground/busy_ring.yaml): one walks
// ahead of the robot at its pace along the first side. Its back, paired with where the last
// keyframe saw it, held the robot still while it drove on: 34 m off by the corner. Left out where
// the beams had seen empty space (free_space), and so out of the match and the map.
TEST_F(UavslamCli, APersonWalkingAheadAtTheRobotsPaceDoesNotHoldItStill) {
  const GroundLog busy = simulate_ground(dir, "busy_ring");

  const ScoredRun left_out = run_and_score(busy, dir / "left_out");
  EXPECT_GT(left_out.summary["scans"]["moving_points"]["points"].get<int>(), 1000);
  EXPECT_LT(left_out.mean, 0.03);
  EXPECT_LT(left_out.max, 0.5);

  const ScoredRun matched = run_and_score(busy, dir / "matched", "--set free_space.enabled=false");
  EXPECT_EQ(matched.summary["scans"]["moving_points"]["points"].get<int>(), 0);
  EXPECT_GT(matched.max, 5.0);
}

// The corridor with a person walking down it ahead of the UAV at its pace
// (config/scenarios/corridor_follower.yaml). Matched as a wall, their back held the estimate
// metres behind the vehicle; left out where the scans' slab of the building had been seen empty
// (free_space, on in config/slam.yaml), the flight is as good as in the empty corridor. The
// person passes the UAV as it climbs, and its floor beams measure the height: neither is lost.
TEST_F(UavslamCli, APersonWalkingAheadOfTheUavDoesNotHoldItBack) {
  const nlohmann::json left_out =
      simulate(dir / "left_out", "corridor_follower", "config/slam.yaml");
  EXPECT_LT(ate_horizontal(left_out), 0.15);
  EXPECT_LT(left_out.at("trajectory_errors").at("ate_vertical_rmse_m").get<double>(), 0.05);
  EXPECT_GT(left_out.at("scans").at("height_from_floor").get<int>(), 3000);
  EXPECT_GT(left_out.at("scans").at("moving_points").at("points").get<int>(), 1000);

  const nlohmann::json matched = simulate(dir / "matched", "corridor_follower", "config/slam.yaml",
                                          "--set free_space.enabled=false");
  EXPECT_EQ(matched.at("scans").at("moving_points").at("points").get<int>(), 0);
  EXPECT_GT(ate_horizontal(matched), 1.0);
}

TEST_F(UavslamCli, OfflineNeedsExactlyOneInput) {
  const CommandResult none = run("offline --out " + (dir / "o").string());
  EXPECT_NE(none.exit_code, 0);
  EXPECT_THAT(none.output, HasSubstr("--carmen"));
  const CommandResult both =
      run("offline --carmen " + source("config/slam.yaml") + " --scenario " +
          source("config/scenarios/short.yaml") + " --out " + (dir / "o").string());
  EXPECT_NE(both.exit_code, 0);
  EXPECT_FALSE(fs::exists(dir / "o"));
}

// The short flight recorded by `uavslam simulate --log` (MCAP: scan, imu, ground_truth), and the
// simulation's summary.json beside it.
struct RecordedFlight {
  std::string log;
  nlohmann::json summary;
};

RecordedFlight record_short_flight(const fs::path& dir) {
  const std::string log = (dir / "short.mcap").string();
  const CommandResult r =
      run("simulate --quiet --scenario " + source("config/scenarios/short.yaml") + " --config " +
          source("config/seed.yaml") + " --out " + (dir / "simulate").string() + " --log " + log);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  std::ifstream json(dir / "simulate" / "summary.json");
  return {log, nlohmann::json::parse(json, nullptr, false)};
}

// The recorded flight mapped offline with its sensor: at least as accurate as the real-time pass
// over the same recording, the cloud on the true surfaces, every simulated scan read back.
TEST_F(UavslamCli, OfflineMapsARecordedFlight) {
  const RecordedFlight flight = record_short_flight(dir);
  ASSERT_FALSE(HasFailure());
  const fs::path out = dir / "offline";
  const CommandResult r = run("offline --quiet --log " + flight.log + " --sensor " +
                              source("config/scenarios/short.yaml") + " --config " +
                              source("config/seed.yaml") + " --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream json(out / "report.json");
  const nlohmann::json report = nlohmann::json::parse(json);
  const nlohmann::json& offline = report.at("offline");
  const nlohmann::json& realtime = report.at("realtime");
  const std::size_t simulated = flight.summary.at("scans").at("in").get<std::size_t>();
  EXPECT_EQ(simulated, 801u);
  EXPECT_EQ(offline.at("scans").get<std::size_t>(), simulated);
  EXPECT_EQ(realtime.at("scans").get<std::size_t>(), simulated);
  const double offline_ate = offline.at("errors").at("ate_rmse_m").get<double>();
  const double realtime_ate = realtime.at("errors").at("ate_rmse_m").get<double>();
  EXPECT_LE(offline_ate, realtime_ate) << r.output;
  // The real-time pass over the recording is the simulation's run over the same data (the seed's
  // config: the IMU prior integrates a sample stamped at a scan's time only if it came first, and
  // the recording and the simulation order such samples differently).
  EXPECT_NEAR(realtime_ate, flight.summary.at("trajectory_errors").at("ate_rmse_m").get<double>(),
              1e-9);
  EXPECT_LT(offline.at("cloud").at("distance_to_true_surfaces").at("mean_m").get<double>(), 0.03)
      << r.output;
  EXPECT_FALSE(report.contains("input_damage"));
}

// A flight with the autopilot's velocity (flow_corridor.yaml) recorded by `simulate --log`: the
// recording carries the velocity channel, and the real-time pass over it is, to the IMU samples'
// order, the simulation's run, velocity fused (the IMU alone would end metres off).
TEST_F(UavslamCli, ARecordedFlightKeepsTheAutopilotsVelocity) {
  const std::string log = (dir / "flow.mcap").string();
  const CommandResult simulated =
      run("simulate --quiet --scenario " + source("config/scenarios/flow_corridor.yaml") +
          " --config " + source("config/slam.yaml") + " --out " + (dir / "simulate").string() +
          " --log " + log);
  ASSERT_EQ(simulated.exit_code, 0) << simulated.output;
  std::ifstream summary_file(dir / "simulate" / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(summary_file);
  const fs::path out = dir / "offline";
  const CommandResult r = run("offline --quiet --log " + log + " --sensor " +
                              source("config/scenarios/flow_corridor.yaml") + " --config " +
                              source("config/slam.yaml") + " --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream json(out / "report.json");
  const nlohmann::json report = nlohmann::json::parse(json);
  const double realtime_ate = report.at("realtime").at("errors").at("ate_rmse_m").get<double>();
  // Not bit for bit: the IMU prior integrates a sample stamped at a scan's time only if it came
  // first, and the recording orders those differently (OfflineMapsARecordedFlight uses the seed's
  // config for that reason); without the velocity the IMU alone ends metres off.
  EXPECT_NEAR(realtime_ate, summary.at("trajectory_errors").at("ate_rmse_m").get<double>(), 0.005);
  EXPECT_LT(realtime_ate, 0.15);
}

// A recording cut in the middle (a recorder that was killed): the whole chunks before the cut are
// mapped, and the report and the exit code (1) say where it stopped.
TEST_F(UavslamCli, OfflineMapsTheCompletePartOfACutLog) {
  const RecordedFlight flight = record_short_flight(dir);
  ASSERT_FALSE(HasFailure());
  const std::string cut = (dir / "cut.mcap").string();
  fs::copy_file(flight.log, cut);
  fs::resize_file(cut, fs::file_size(flight.log) / 2);
  const fs::path out = dir / "offline";
  const CommandResult r = run("offline --quiet --skip-realtime --log " + cut + " --sensor " +
                              source("config/scenarios/short.yaml") + " --out " + out.string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("cut short"));
  std::ifstream json(out / "report.json");
  const nlohmann::json report = nlohmann::json::parse(json);
  EXPECT_THAT(report.at("input_damage").get<std::string>(),
              HasSubstr(cut + ": the log stops at byte"));
  const std::size_t scans = report.at("offline").at("scans").get<std::size_t>();
  EXPECT_GT(scans, 100u);
  EXPECT_LT(scans, 801u);
  EXPECT_EQ(report.at("offline").at("posed").get<std::size_t>(), scans);
  EXPECT_LT(report.at("offline").at("errors").at("ate_rmse_m").get<double>(), 0.1);
}

// The messages of `from` whose topic `rename` gives new topics, each written once per new topic
// (none: the channel is left out).
void copy_channels(const std::string& from, const std::string& to,
                   const std::function<std::vector<std::string>(const std::string&)>& rename) {
  uavslam::io::McapStreamReader reader(from);
  uavslam::io::McapWriter writer(to);
  uavslam::io::mcap::Message message;
  std::map<std::pair<std::uint16_t, std::string>, std::uint16_t> channels;  // ours by source, topic
  while (reader.next(message)) {
    const uavslam::io::mcap::Channel& c = reader.channels().at(message.channel_id);
    for (const std::string& topic : rename(c.topic)) {
      std::uint16_t& channel = channels[{message.channel_id, topic}];
      if (channel == 0) {
        const uavslam::io::mcap::Schema& s = reader.schemas().at(c.schema_id);
        channel = writer.add_channel(writer.add_schema(s.name, s.encoding, s.data), topic,
                                     c.message_encoding, c.metadata);
      }
      writer.write(channel, message.sequence, message.log_time, message.publish_time,
                   message.data.data(), message.data.size());
    }
  }
  writer.close();
}

TEST_F(UavslamCli, OfflineRefusesALogWithScansButNoImu) {
  const RecordedFlight flight = record_short_flight(dir);
  ASSERT_FALSE(HasFailure());
  const std::string scans_only = (dir / "scans_only.mcap").string();
  copy_channels(flight.log, scans_only, [](const std::string& topic) {
    return topic == "scan" ? std::vector<std::string>{topic} : std::vector<std::string>{};
  });
  const CommandResult r =
      run("offline --quiet --log " + scans_only + " --out " + (dir / "o").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr(scans_only + ": its 801 scans"));
  EXPECT_THAT(r.output, HasSubstr("no imu channel: nothing to orient them"));
  EXPECT_FALSE(fs::exists(dir / "o"));
}

TEST_F(UavslamCli, OfflineMapsTheVehicleItIsToldOfAFleetsRecording) {
  const RecordedFlight flight = record_short_flight(dir);
  ASSERT_FALSE(HasFailure());
  const std::string fleet = (dir / "fleet.mcap").string();
  copy_channels(flight.log, fleet, [](const std::string& topic) {  // a fleet's recording
    return std::vector<std::string>{"uav1/" + topic, "uav2/" + topic};
  });
  const std::string common = "offline --quiet --skip-realtime --log " + fleet + " --out ";

  const CommandResult unnamed = run(common + (dir / "o1").string());
  EXPECT_EQ(unnamed.exit_code, 2) << unnamed.output;
  EXPECT_THAT(unnamed.output, HasSubstr("several vehicles' scans"));
  EXPECT_THAT(unnamed.output, HasSubstr("choose one with --vehicle"));
  const CommandResult unknown = run(common + (dir / "o3").string() + " --vehicle uav3");
  EXPECT_EQ(unknown.exit_code, 2) << unknown.output;
  EXPECT_THAT(unknown.output, HasSubstr("no uav3/scan channel for --vehicle uav3"));

  const fs::path out = dir / "o2";
  const CommandResult named = run(common + out.string() + " --vehicle uav2");
  ASSERT_EQ(named.exit_code, 0) << named.output;
  std::ifstream json(out / "report.json");
  const nlohmann::json report = nlohmann::json::parse(json);
  EXPECT_EQ(report.at("offline").at("scans").get<int>(), 801) << report.dump(2);
}

TEST_F(UavslamCli, OfflineNamesAFileThatIsNotMcap) {
  const CommandResult r =
      run("offline --log " + source("config/slam.yaml") + " --out " + (dir / "o").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr(source("config/slam.yaml") + ": not an MCAP file"));
  const CommandResult sensor_alone =
      run("offline --scenario " + source("config/scenarios/short.yaml") + " --sensor " +
          source("config/scenarios/short.yaml") + " --out " + (dir / "o").string());
  EXPECT_NE(sensor_alone.exit_code, 0);
  EXPECT_THAT(sensor_alone.output, HasSubstr("--log"));
}
