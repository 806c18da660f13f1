#include "io/SimulatedCarmenLog.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/Angles.hpp"
#include "core/Heading.hpp"
#include "core/PlanarPose.hpp"
#include "eval/TruthRelations.hpp"
#include "io/CarmenWriter.hpp"
#include "io/RelationsFile.hpp"
#include "sim/WheelOdometry.hpp"

namespace uavslam::io {
namespace {

struct PlanarBeams {
  double start_angle = 0.0;
  double increment = 0.0;
};

// The beams as CARMEN states them: a start angle and a step, in the sensor's x-y plane.
PlanarBeams planar_beams(const ScanGeometry& geometry) {
  const std::vector<Vec3>& d = geometry.directions;
  if (d.size() < 2) throw std::invalid_argument("a CARMEN log needs a scanner of 2 or more beams");
  PlanarBeams beams;
  beams.start_angle = std::atan2(d[0].y(), d[0].x());
  beams.increment = wrap_angle(std::atan2(d[1].y(), d[1].x()) - beams.start_angle);
  for (std::size_t i = 0; i < d.size(); ++i) {
    const double expected = beams.start_angle + static_cast<double>(i) * beams.increment;
    const double angle = std::atan2(d[i].y(), d[i].x());
    if (std::abs(d[i].z()) > 1e-9 || std::abs(wrap_angle(angle - expected)) > 1e-9) {
      std::ostringstream what;
      what << "a CARMEN log needs a planar scanner with evenly spaced beams; beam " << i
           << " points at (" << d[i].x() << ", " << d[i].y() << ", " << d[i].z() << ")";
      throw std::invalid_argument(what.str());
    }
  }
  return beams;
}

// The laser's mount on the robot as a planar pose.
PlanarPose planar_mount(const Eigen::Isometry3d& mount) {
  const Eigen::Quaterniond rotation(mount.rotation());
  if (tilt_of(rotation) > 1e-9) {
    throw std::invalid_argument("a CARMEN log needs a level scanner; the mount is tilted");
  }
  return {mount.translation().x(), mount.translation().y(), heading_of(rotation)};
}

CarmenPose2 carmen_pose(const PlanarPose& p) {
  return {p.x, p.y, p.theta};
}

std::vector<std::string> header(const sim::Scenario& scenario) {
  const sim::WheelOdometrySpec& o = scenario.odometry;
  std::ostringstream odometry;
  odometry << "wheel odometry: scale errors " << o.translation_scale_error << " (translation), "
           << o.turn_scale_error << " (turn); noise " << o.translation_noise << " m/sqrt(m), "
           << o.turn_noise << " rad/sqrt(rad), " << o.turn_per_metre_noise << " rad/sqrt(m)";
  std::ostringstream seed;
  seed << "seed " << scenario.seed;
  return {"CARMEN log of the simulated scenario " + scenario.name + " (uavslam simulate --carmen)",
          odometry.str(), seed.str()};
}

}  // namespace

SimulatedCarmenFiles write_simulated_carmen_log(const std::string& log_path,
                                                const std::string& relations_path,
                                                const sim::Scenario& scenario,
                                                const std::vector<Scan>& scans,
                                                const std::vector<Pose>& truth) {
  if (scans.size() != truth.size()) {
    throw std::invalid_argument("a true pose is needed for every scan");
  }
  SimulatedCarmenFiles files;
  if (scans.empty()) return files;
  const ScanGeometry& geometry = *scans.front().geometry;
  const PlanarBeams beams = planar_beams(geometry);
  const PlanarPose mount = planar_mount(geometry.mount);
  const std::vector<PlanarPose> odometry =
      sim::wheel_odometry(truth, scenario.odometry, scenario.seed);

  std::vector<CarmenMessage> messages;
  std::vector<eval::PlanarStamped> true_path;
  messages.reserve(2 * scans.size());
  for (std::size_t i = 0; i < scans.size(); ++i) {
    const double stamp = scans[i].stamp;
    CarmenOdometry odom;
    odom.pose = carmen_pose(odometry[i]);
    odom.ipc_timestamp = stamp;
    if (i > 0 && stamp > scans[i - 1].stamp) {
      const double dt = stamp - scans[i - 1].stamp;
      odom.tv =
          std::hypot(odometry[i].x - odometry[i - 1].x, odometry[i].y - odometry[i - 1].y) / dt;
      odom.rv = wrap_angle(odometry[i].theta - odometry[i - 1].theta) / dt;
    }
    messages.emplace_back(odom);
    CarmenScan scan;
    scan.message = CarmenScan::Message::robotlaser1;
    scan.ipc_timestamp = stamp;
    scan.start_angle = beams.start_angle;
    scan.angle_increment = beams.increment;
    scan.max_range = geometry.max_range;
    scan.ranges = scans[i].ranges;
    scan.robot_pose = odom.pose;
    scan.laser_pose = carmen_pose(compose(odometry[i], mount));
    messages.emplace_back(std::move(scan));
    const PlanarPose p = planar_pose(truth[i]);
    true_path.push_back({stamp, p.x, p.y, p.theta});
    if (i > 0) {
      files.path_length += std::hypot(p.x - true_path[i - 1].x, p.y - true_path[i - 1].y);
    }
  }
  write_carmen_log(log_path, header(scenario), messages);
  const std::vector<eval::Relation> relations = eval::relations_from_truth(true_path);
  write_relations(relations_path, relations);
  files.scans = scans.size();
  files.relations = relations.size();
  return files;
}

}  // namespace uavslam::io
