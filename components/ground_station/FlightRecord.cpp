#include "FlightRecord.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "eval/Percentile.hpp"
#include "io/FileError.hpp"
#include "io/OctreeFile.hpp"
#include "io/PlyFile.hpp"
#include "io/PngFile.hpp"
#include "io/TopDownMapImage.hpp"
#include "io/TumFile.hpp"

namespace uavslam::ground_station {
namespace {

namespace fs = std::filesystem;

std::string fixed(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

nlohmann::json latency_json(const std::vector<double>& latencies_ms) {
  const eval::SampleStats stats = eval::summarize(latencies_ms);
  return {{"count", stats.count},
          {"mean_ms", stats.mean},
          {"p50_ms", stats.p50},
          {"p99_ms", stats.p99},
          {"max_ms", stats.max}};
}

void write_json(const std::string& path, const nlohmann::json& json) {
  std::ofstream out(path);
  out << json.dump(2) << "\n";
  if (!out.flush()) throw io::file_error(path, "cannot write");
}

}  // namespace

// One line per pose: its scan, its stamp, when it arrived (system clock, s) and its scan -> pose
// latency (empty when its scan had not arrived yet).
void FlightRecord::write_arrivals(const std::string& file, const std::vector<Pose>& poses,
                                  const std::vector<Arrival>& arrivals) {
  std::ofstream out(file);
  out << "scan_seq,stamp,received_at,latency_ms\n";
  char line[128];
  for (std::size_t i = 0; i < arrivals.size() && i < poses.size(); ++i) {
    const Arrival& a = arrivals[i];
    std::snprintf(line, sizeof line, "%llu,%.6f,%.6f,", static_cast<unsigned long long>(a.scan_seq),
                  poses[i].stamp, a.received_at);
    out << line;
    if (a.latency_ms) {
      std::snprintf(line, sizeof line, "%.3f", *a.latency_ms);
      out << line;
    }
    out << "\n";
  }
  if (!out.flush()) throw io::file_error(file, "cannot write");
}

FlightRecord::FlightRecord(std::size_t latency_window) : latency_join_(latency_window) {}

void FlightRecord::add_pose(const Pose& pose, std::uint64_t scan_seq, double received_at) {
  std::lock_guard<std::mutex> lock(mutex_);
  poses_.push_back(pose);
  if (!first_pose_at_) first_pose_at_ = received_at;
  last_pose_at_ = received_at;
  const std::optional<double> ms = latency_join_.add_pose(scan_seq, received_at);
  if (ms) latencies_ms_.push_back(*ms);
  arrivals_.push_back({scan_seq, received_at, ms});
}

void FlightRecord::add_malformed_pose() {
  std::lock_guard<std::mutex> lock(mutex_);
  ++malformed_poses_;
}

void FlightRecord::add_scan(std::uint64_t scan_seq, double published_at) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (const auto ms = latency_join_.add_scan(scan_seq, published_at)) latencies_ms_.push_back(*ms);
}

void FlightRecord::set_matcher_status(const MatcherCounters& counters) {
  std::lock_guard<std::mutex> lock(mutex_);
  counters_ = counters;
  ++statuses_;
}

void FlightRecord::set_map(std::shared_ptr<const octomap::OcTree> tree,
                           const MapSnapshotInfo& info) {
  std::lock_guard<std::mutex> lock(mutex_);
  map_ = std::move(tree);
  map_info_ = info;
  ++maps_;
}

void FlightRecord::add_malformed_map() {
  std::lock_guard<std::mutex> lock(mutex_);
  ++malformed_maps_;
}

std::string FlightRecord::status_line() {
  std::lock_guard<std::mutex> lock(mutex_);
  const Clock::time_point now = Clock::now();
  const double seconds = std::chrono::duration<double>(now - line_time_).count();
  const double rate = seconds > 0 ? (poses_.size() - line_poses_) / seconds : 0.0;
  std::string line = "gcs: " + fixed(rate, 1) + " Hz pose, latency ";
  const std::vector<double> recent(latencies_ms_.begin() + static_cast<long>(line_latencies_),
                                   latencies_ms_.end());
  if (recent.empty()) {
    line += "-";
  } else {
    const eval::SampleStats stats = eval::summarize(recent);
    line += "p50 " + fixed(stats.p50, 1) + " ms p99 " + fixed(stats.p99, 1) + " ms";
  }
  if (statuses_ == 0) {
    line += ", no matcher status yet";
  } else {
    line += ", " + counters_.tracking;
    if (!counters_.tracking_reason.empty()) line += " (" + counters_.tracking_reason + ")";
    line += ", accepted " + std::to_string(counters_.scans_accepted) + " rejected " +
            std::to_string(counters_.scans_rejected) + " skipped " +
            std::to_string(counters_.scans_skipped);
  }
  if (maps_ == 0) {
    line += ", no map yet";
  } else {
    line += ", map " + std::to_string(map_info_.map_points) + " pts / " +
            std::to_string(map_info_.occupied_cells) + " occupied cells (snapshot " +
            std::to_string(map_info_.map_seq) + ")";
  }
  if (malformed_poses_ + malformed_maps_ > 0) {
    line += ", dropped " + std::to_string(malformed_poses_) + " bad poses " +
            std::to_string(malformed_maps_) + " bad maps";
  }
  line_time_ = now;
  line_poses_ = poses_.size();
  line_latencies_ = latencies_ms_.size();
  return line;
}

void FlightRecord::add_correction(backend::StampedKeyframes correction) {
  std::lock_guard<std::mutex> lock(mutex_);
  corrections_.push_back(std::move(correction));
}

nlohmann::json FlightRecord::summary() const {
  std::lock_guard<std::mutex> lock(mutex_);
  const double span = first_pose_at_ ? last_pose_at_ - *first_pose_at_ : 0.0;
  nlohmann::json json;
  json["poses"] = {{"received", poses_.size()},
                   {"malformed", malformed_poses_},
                   {"rate_hz", span > 0 ? (poses_.size() - 1) / span : 0.0}};
  json["latency_scan_to_pose"] = latency_json(latencies_ms_);
  json["matcher_status"] = {{"received", statuses_},
                            {"scans_received", counters_.scans_received},
                            {"scans_skipped", counters_.scans_skipped},
                            {"scans_rejected", counters_.scans_rejected},
                            {"scans_accepted", counters_.scans_accepted},
                            {"last_outcome", counters_.last_outcome},
                            {"last_tracking", counters_.tracking},
                            {"last_tracking_reason", counters_.tracking_reason},
                            {"loops_searched", counters_.loops_searched},
                            {"loops_accepted", counters_.loops_accepted},
                            {"corrections", counters_.corrections},
                            {"heading_drift_deg_per_min", counters_.heading_drift_deg_per_min}};
  json["map"] = {{"snapshots_received", maps_},
                 {"malformed", malformed_maps_},
                 {"last_map_seq", maps_ > 0 ? nlohmann::json(map_info_.map_seq) : nlohmann::json()},
                 {"occupied_cells", map_info_.occupied_cells},
                 {"map_points", map_info_.map_points},
                 {"resolution_m", map_info_.resolution}};
  json["back_end"] = {
      {"corrections_received", corrections_.size()},
      {"keyframes_corrected", corrections_.empty() ? 0 : corrections_.back().keyframes.size()}};
  json["files"] = files_;
  if (picture_) json["map_topdown"] = *picture_;
  return json;
}

std::vector<std::string> FlightRecord::write_outputs(const std::string& dir) {
  std::error_code error;
  fs::create_directories(dir, error);
  if (error) throw io::file_error(dir, "cannot create directory: " + error.message());
  std::vector<Pose> poses;
  std::vector<backend::StampedKeyframes> corrections;
  std::vector<Arrival> arrivals;
  std::shared_ptr<const octomap::OcTree> map;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    poses = poses_;
    corrections = corrections_;
    arrivals = arrivals_;
    map = map_;
  }
  auto path = [&](const char* name) { return (fs::path(dir) / name).string(); };
  std::vector<std::string> files{"trajectory.tum", "pose_arrivals.csv"};
  io::write_tum(path("trajectory.tum"), poses);
  write_arrivals(path("pose_arrivals.csv"), poses, arrivals);
  if (!corrections.empty()) {
    // In the order of the poses they apply from (DDS may deliver two out of order).
    const auto by_stamp = [](const auto& a, const auto& b) { return a.stamp < b.stamp; };
    std::stable_sort(corrections.begin(), corrections.end(), by_stamp);
    std::vector<Pose> by_time = poses;
    std::stable_sort(by_time.begin(), by_time.end(), by_stamp);
    io::write_tum(path("keyframes.tum"), corrections.back().keyframes);
    io::write_tum(path("trajectory_corrected.tum"),
                  backend::corrected_trajectory(by_time, corrections));
    files.insert(files.end(), {"keyframes.tum", "trajectory_corrected.tum"});
  }
  if (map) {
    io::write_bt(path("map.bt"), *map);
    io::write_ply(path("map_occupied.ply"), io::occupied_cell_centres(*map));
    files.insert(files.end(), {"map.bt", "map_occupied.ply"});
  }
  std::optional<nlohmann::json> picture;
  if (map || !poses.empty()) {
    const io::TopDownMap image = io::render_top_down(map.get(), poses);
    io::write_png(path("map_topdown.png"), image.image);
    files.push_back("map_topdown.png");
    picture = nlohmann::json{{"width_px", image.view.width},
                             {"height_px", image.view.height},
                             {"pixels_per_metre", image.view.pixels_per_metre},
                             {"scale_bar_m", image.scale_bar_m},
                             {"left_x_m", image.view.min_x},
                             {"top_y_m", image.view.max_y},
                             {"margin_px", image.view.margin_px}};
  }
  files.push_back("summary.json");
  {
    std::lock_guard<std::mutex> lock(mutex_);
    files_ = files;
    picture_ = picture;
  }
  write_json(path("summary.json"), summary());
  return files;
}

}  // namespace uavslam::ground_station
