// slam_matcher: subscribes `scan` and `imu`, runs the vehicle's SLAM (src/slam/VehicleSlam) on the
// waiting scans, publishes `pose`, `map_points` and `matcher_status`. The sensor (mount, floor
// mirror, beam layout) comes from the `lidar` section of a scenario or sensor YAML, or, with
// --geometry-from-scan, from each scan message as a planar scanner at the body origin (replayed
// 2D logs: lidar_driver --source carmen:FILE). With `icp.motion_prior: odometry` in the SLAM
// config it also subscribes `odom` (wheel odometry, imu_bridge --source carmen:FILE) and gives each
// scan the odometry's motion since the last scan that got a pose as the ICP's start; with
// `icp.motion_prior: imu` and `motion.fuse_velocity` it subscribes `velocity` (the autopilot's
// estimate, imu_bridge) and the IMU prior fuses it.
#include <chrono>
#include <cmath>
#include <iostream>
#include <memory>

#include <msg/ImuPubSubTypes.h>
#include <msg/KeyframePosesPubSubTypes.h>
#include <msg/LaserScanPubSubTypes.h>
#include <msg/MapPointsPubSubTypes.h>
#include <msg/MatcherStatusPubSubTypes.h>
#include <msg/PosePubSubTypes.h>
#include <msg/TwistPubSubTypes.h>
#include <CLI/CLI.hpp>

#include "ScanQueue.hpp"
#include "common/IncompatibleQos.hpp"
#include "common/NodeOptions.hpp"
#include "common/RunNode.hpp"
#include "common/StopRequest.hpp"
#include "dds/Conversions.hpp"
#include "dds/MatcherMessages.hpp"
#include "dds/MessageScanGeometry.hpp"
#include "dds/Participant.hpp"
#include "dds/Reader.hpp"
#include "dds/Topics.hpp"
#include "dds/Writer.hpp"
#include "io/ScenarioFile.hpp"
#include "io/SlamConfigFile.hpp"
#include "slam/VehicleSlam.hpp"

namespace uavslam {
namespace {
constexpr double kDegreesPerRadian = 57.29577951308232;  // 180 / pi

struct MatcherOptions {
  std::string sensor = "config/scenarios/demo.yaml";
  std::string slam_config;
  std::vector<double> initial_position;  // empty: the scenario's first waypoint
  bool geometry_from_scan = false;       // the beam layout of each scan message; no sensor file
  double max_scan_backlog_s = matcher::ScanQueue::kDefaultBacklog;
};

double wall_seconds() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

double to_seconds(const eprosima::fastrtps::rtps::Time_t& t) {
  return t.seconds() + t.nanosec() * 1e-9;
}

class MatcherNode {
 public:
  MatcherNode(const process::NodeOptions& node, const MatcherOptions& o)
      : vehicle_(node.vehicle),
        sensor_(o.geometry_from_scan ? io::SensorFile{} : io::load_sensor(o.sensor)),
        geometries_(o.geometry_from_scan ? dds::MessageScanGeometry()
                                         : dds::MessageScanGeometry(sensor_.sensor.lidar)),
        // The back end on its own thread: the scan's path never waits for a loop search.
        slam_(o.slam_config.empty() ? SlamConfig{} : io::load_slam_config(o.slam_config), {},
              BackendThreading::Thread),
        queue_(uses_odometry(), o.max_scan_backlog_s),
        max_scan_backlog_s_(o.max_scan_backlog_s),
        participant_(node.domain, process::profiles_path(node), node.participant_profile,
                     "slam_matcher"),
        pose_(participant_, dds::topic_name(vehicle_, dds::kPoseTopic),
              node.profile(dds::kPoseTopic, "state_writer")),
        map_points_(participant_, dds::topic_name(vehicle_, dds::kMapPointsTopic),
                    node.profile(dds::kMapPointsTopic, "map_points_writer")),
        keyframe_poses_(participant_, dds::topic_name(vehicle_, dds::kKeyframePosesTopic),
                        node.profile(dds::kKeyframePosesTopic, "map_writer")),
        status_(participant_, dds::topic_name(vehicle_, dds::kMatcherStatusTopic),
                node.profile(dds::kMatcherStatusTopic, "status_writer")),
        scans_(participant_, dds::topic_name(vehicle_, dds::kScanTopic),
               node.profile(dds::kScanTopic, "sensor_reader"),
               [this](const msg::LaserScan& m, const eprosima::fastdds::dds::SampleInfo& info) {
                 queue_.push_scan({m, to_seconds(info.source_timestamp)});
               }),
        odometry_(make_odometry_reader(node)),
        velocity_(make_velocity_reader(node)),
        imu_(participant_, dds::topic_name(vehicle_, dds::kImuTopic),
             node.profile(dds::kImuTopic, "sensor_reader"),
             [this](const msg::Imu& m, const eprosima::fastdds::dds::SampleInfo&) {
               queue_.push_imu(dds::from_msg(m));
             }) {
    slam_.start_at(initial_position(o));
  }

  int run() {
    std::cerr << "slam_matcher: matching " << dds::topic_name(vehicle_, dds::kScanTopic)
              << (geometries_.sensor_geometry() ? " with the sensor of " + sensor_.sensor.name
                                                : " with the beam layout of each scan")
              << "\n";
    while (!process::stop_requested()) {
      check_qos();
      auto work =
          queue_.wait_for_scan(std::chrono::milliseconds(100), std::chrono::milliseconds(20));
      if (work) process(*work);
    }
    print_summary();
    return qos_.exit_code();
  }

 private:
  bool uses_odometry() const { return slam_.odometry_prior() != nullptr; }

  void check_qos() {
    qos_.input(scans_);
    qos_.input(imu_);
    if (odometry_) qos_.input(*odometry_);
    if (velocity_) qos_.input(*velocity_);
    qos_.output(pose_);
    qos_.output(map_points_);
    qos_.output(status_);
  }

  Vec3 initial_position(const MatcherOptions& o) const {
    if (o.initial_position.size() == 3) {
      return {o.initial_position[0], o.initial_position[1], o.initial_position[2]};
    }
    return sensor_.take_off.value_or(Vec3::Zero());
  }

  // Created before the imu reader: an imu_bridge waiting for its imu subscribers then finds this
  // one matched too (the same participant announces its readers in order).
  std::unique_ptr<dds::Reader<msg::PoseWithCovarianceStampedPubSubType>> make_odometry_reader(
      const process::NodeOptions& node) {
    if (!uses_odometry()) return nullptr;
    return std::make_unique<dds::Reader<msg::PoseWithCovarianceStampedPubSubType>>(
        participant_, dds::topic_name(vehicle_, dds::kOdometryTopic),
        node.profile(dds::kOdometryTopic, "sensor_reader"),
        [this](const msg::PoseWithCovarianceStamped& m, const eprosima::fastdds::dds::SampleInfo&) {
          const Pose pose = dds::from_msg(m);
          queue_.push_odometry({pose.stamp, pose.position});
        });
  }

  // The autopilot's velocity, with the IMU prior and motion.fuse_velocity; created before the imu
  // reader as the odometry's is.
  std::unique_ptr<dds::Reader<msg::TwistWithCovarianceStampedPubSubType>> make_velocity_reader(
      const process::NodeOptions& node) {
    if (!slam_.inertial_prior() || !slam_.config().motion.fuse_velocity) return nullptr;
    return std::make_unique<dds::Reader<msg::TwistWithCovarianceStampedPubSubType>>(
        participant_, dds::topic_name(vehicle_, dds::kVelocityTopic),
        node.profile(dds::kVelocityTopic, "sensor_reader"),
        [this](const msg::TwistWithCovarianceStamped& m,
               const eprosima::fastdds::dds::SampleInfo&) {
          queue_.push_velocity(dds::from_msg(m));
        });
  }

  void process(matcher::ScanQueue::Work& work) {
    for (const ImuSample& sample : work.imu) slam_.add_imu(sample);
    for (const OdometrySample& sample : work.odometry) slam_.add_odometry(sample);
    for (const VelocitySample& sample : work.velocity) slam_.add_velocity(sample);
    const Scan scan = dds::from_msg(work.scan.message, geometry_for(work.scan.message));
    const std::uint64_t skipped = queue_.scans_skipped();
    const VehicleScan result = slam_.process_scan(scan, skipped - counts_.skipped);
    const dds::Source source{"map", vehicle_};
    // A rejected scan that the motion prior carried still gets its pose, with quality 0 and the
    // prior's covariance: whoever flies on `pose` hears of the vehicle at every scan.
    if (result.posed()) {
      pose_.write(
          dds::pose_message(result.report, slam_.config(), scan.sequence, poses_++, source));
      dead_reckoned_ += result.report.dead_reckoned;
    }
    counts_.accepted += result.report.accepted();
    // The back end moved the keyframes: every one where it now is, before the newest keyframe
    // goes out in the corrected frame.
    if (result.map_corrected) {
      keyframe_poses_.write(dds::keyframe_poses_message(slam_.keyframe_poses(),
                                                        slam_.keyframe_stamps(), scan.stamp,
                                                        ++counts_.corrections, source));
    }
    if (result.keyframe) map_points_.write(dds::keyframe_message(*result.keyframe, source));
    counts_.rejected += !result.report.accepted();
    counts_.received = queue_.scans_received();
    counts_.skipped = skipped;
    if (const std::optional<backend::LoopCounts> loops = slam_.loops()) counts_.loops = *loops;
    status_.write(dds::status_message(result, scan, (wall_seconds() - work.scan.published_at) * 1e3,
                                      counts_, statuses_++, source));
  }

  // The sensor file's geometry, or the scan's own layout (said once when it differs).
  std::shared_ptr<const ScanGeometry> geometry_for(const msg::LaserScan& message) {
    std::shared_ptr<const ScanGeometry> geometry = geometries_.for_message(message);
    if (geometries_.own_layout_used() && !layout_noted_) {
      layout_noted_ = true;
      std::cerr << "slam_matcher: the scans have " << message.ranges().size() << " beams from "
                << message.angle_min() * kDegreesPerRadian << " deg by "
                << message.angle_increment() * kDegreesPerRadian << " deg, " << sensor_.sensor.name
                << "'s lidar " << geometries_.sensor_geometry()->directions.size()
                << ": matching them with their own layout, mounted as the sensor file says\n";
    }
    if (slam_.config().scan.deskew && !sweep_noted_) {
      sweep_noted_ = true;
      if (geometry->fire_times.empty()) {
        std::cerr << "slam_matcher: scan.deskew is on, but the scans say nothing of when their "
                     "beams fire (no time_increment, no lidar.sweep_seconds in the sensor file): "
                     "every beam is placed from the scan's stamp\n";
      } else {
        std::cerr << "slam_matcher: each beam placed from where the vehicle was when it fired "
                     "(scan.deskew), over a sweep of "
                  << geometry->sweep_seconds() * 1e3 << " ms\n";
      }
    }
    return geometry;
  }

  void print_summary() const {
    std::cerr << "slam_matcher: " << queue_.scans_received() << " scans received, "
              << queue_.scans_skipped() << " skipped (over " << max_scan_backlog_s_
              << " s behind a newer one), " << poses_ << " poses published (" << dead_reckoned_
              << " dead-reckoned), " << counts_.rejected << " rejected, map "
              << slam_.pipeline().map().size() << " points from " << slam_.keyframes()
              << " keyframes\n";
    if (const OdometryPrior* prior = slam_.odometry_prior()) {
      std::cerr << "slam_matcher: odometry prior: " << queue_.odometry_received()
                << " odometry samples received, " << prior->rejected()
                << " dropped (non-finite or out of order), " << prior->scans_with_prior()
                << " scans matched with the prior, " << prior->scans_without_prior()
                << " without (no odometry near the scan or the last posed scan)\n";
    }
    if (const std::optional<backend::LoopCounts> loops = slam_.loops()) {
      std::cerr << "slam_matcher: loops: " << backend::describe(*loops) << "; "
                << counts_.corrections << " corrections published\n";
    }
    if (velocity_) {
      std::cerr << "slam_matcher: velocity: " << queue_.velocity_received() << " samples received, "
                << slam_.inertial_prior()->rejected_velocities()
                << " dropped (non-finite, out of order or without a stated accuracy)\n";
    }
  }

  std::string vehicle_;
  io::SensorFile sensor_;
  dds::MessageScanGeometry geometries_;
  VehicleSlam slam_;
  matcher::ScanQueue queue_;
  double max_scan_backlog_s_;
  process::QosWatch qos_{"slam_matcher"};
  dds::Participant participant_;
  dds::Writer<msg::PoseWithCovarianceStampedPubSubType> pose_;
  dds::Writer<msg::MapPointsPubSubType> map_points_;
  dds::Writer<msg::KeyframePosesPubSubType> keyframe_poses_;
  dds::Writer<msg::MatcherStatusPubSubType> status_;
  dds::Reader<msg::LaserScanPubSubType> scans_;
  std::unique_ptr<dds::Reader<msg::PoseWithCovarianceStampedPubSubType>> odometry_;   // or none
  std::unique_ptr<dds::Reader<msg::TwistWithCovarianceStampedPubSubType>> velocity_;  // or none
  dds::Reader<msg::ImuPubSubType> imu_;
  dds::MatcherCounts counts_;
  std::uint64_t statuses_ = 0;
  std::uint64_t poses_ = 0;
  std::uint64_t dead_reckoned_ = 0;
  bool layout_noted_ = false;
  bool sweep_noted_ = false;  // said once whether the sweep's motion is undone
};

void apply_own_config(const CLI::App& app, const io::YamlReader& section, MatcherOptions& o) {
  section.expect_keys_only(
      {"sensor", "slam_config", "initial_position", "geometry_from_scan", "max_scan_backlog_s"});
  if (process::unset(app, "--sensor")) o.sensor = section.get_string_or("sensor", o.sensor);
  if (process::unset(app, "--slam-config")) {
    o.slam_config = section.get_string_or("slam_config", o.slam_config);
  }
  if (process::unset(app, "--initial-position") && section.has("initial_position")) {
    const Vec3 p = section.get_vec3("initial_position");
    o.initial_position = {p.x(), p.y(), p.z()};
  }
  if (process::unset(app, "--geometry-from-scan")) {
    o.geometry_from_scan = section.get_bool_or("geometry_from_scan", o.geometry_from_scan);
  }
  if (process::unset(app, "--max-scan-backlog")) {
    o.max_scan_backlog_s = section.get_double_or("max_scan_backlog_s", o.max_scan_backlog_s,
                                                 io::NumberRange::non_negative());
  }
}

}  // namespace
}  // namespace uavslam

int main(int argc, char** argv) {
  CLI::App app{
      "slam_matcher: subscribes scan and imu (and odom with icp.motion_prior: odometry, velocity "
      "with icp.motion_prior: imu and motion.fuse_velocity), runs "
      "the SLAM pipeline, publishes pose, map_points and matcher_status"};
  uavslam::process::NodeOptions node;
  uavslam::MatcherOptions options;
  uavslam::process::add_node_options(app, node);
  app.add_option("--sensor", options.sensor,
                 "YAML whose `lidar` section describes the scanner: a sensor file "
                 "(config/sensors/*.yaml) or a scenario file")
      ->capture_default_str();
  app.add_option("--slam-config", options.slam_config,
                 "SLAM parameters YAML (default: the built-in defaults: the seed, as "
                 "config/seed.yaml; the UAV runs config/slam.yaml); "
                 "with icp.motion_prior: odometry (config/slam_2d_logs.yaml) the matcher also "
                 "subscribes odom and starts each ICP from the odometry's motion since the last "
                 "scan that got a pose");
  app.add_option("--initial-position", options.initial_position,
                 "x,y,z of the body at the first scan (default: the scenario's first waypoint; "
                 "0,0,0 with --geometry-from-scan)")
      ->delimiter(',')
      ->expected(3);
  app.add_flag("--geometry-from-scan", options.geometry_from_scan,
               "take the beam layout from each scan message (angle_min, angle_increment, "
               "range_min/max) as a planar scanner at the body origin, instead of --sensor: for "
               "replayed 2D logs (lidar_driver --source carmen:FILE)");
  app.add_option("--max-scan-backlog", options.max_scan_backlog_s,
                 "seconds (sensor time) a waiting scan may lag the newest one before it is "
                 "skipped: scans arriving in a burst (a lossy link) are all matched, a matcher "
                 "that falls behind keeps to fresh ones; 0 keeps only the newest")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  if (const auto code = uavslam::process::parse_command_line(app, argc, argv)) return *code;
  uavslam::process::install_stop_handler();
  return uavslam::process::run_node("slam_matcher", [&] {
    if (const auto section = uavslam::process::apply_node_config(app, node, "slam_matcher")) {
      uavslam::apply_own_config(app, *section, options);
    }
    uavslam::MatcherNode matcher(node, options);
    return matcher.run();
  });
}
