#!/usr/bin/env bash
# Replays a CARMEN log over DDS (lidar_driver + imu_bridge --source carmen:FILE, odometry on `odom`)
# into the slam_matcher and a ground station, then scores the ground station's trajectory on the
# log's Freiburg relations with `uavslam eval --relations`. The poses' stamps are the replay's
# timeline (io/CarmenTimeline.hpp); each is mapped back to its scan's own ipc_timestamp here, so the
# adjusted stamps (where the log's stamps go back) still meet their relations.
#
#   test/bench/replay_carmen_eval.sh LOG.clf LOG.relations [RATE] [SLAM.yaml] [DOMAIN] [BUILD_DIR]
#
# Defaults: rate 20, config/slam_2d_logs.yaml, domain 196, build/. Output in out/replay_eval/.
set -euo pipefail
cd "$(dirname "$0")/../.."
log=${1:?CARMEN log}
relations=${2:?relations file}
rate=${3:-20}
slam_config=${4:-config/slam_2d_logs.yaml}
domain=${5:-196}
bin=${6:-build}/bin
out=out/replay_eval
rm -rf "$out" && mkdir -p "$out"

"$bin/ground_station" --domain "$domain" --out "$out/ground_station" --no-latency \
  > "$out/ground_station.log" 2>&1 &
station=$!
"$bin/slam_matcher" --domain "$domain" --geometry-from-scan --initial-position 0,0,0 \
  --slam-config "$slam_config" > "$out/slam_matcher.log" 2>&1 &
matcher=$!
start_at=$(($(date +%s) + 3))
"$bin/imu_bridge" --domain "$domain" --source "carmen:$log" --rate "$rate" --start-at "$start_at" \
  --wait-for-subscribers 1 > "$out/imu_bridge.log" 2>&1 &
imu=$!
"$bin/lidar_driver" --domain "$domain" --source "carmen:$log" --rate "$rate" \
  --start-at "$start_at" --wait-for-subscribers 1 > "$out/lidar_driver.log" 2>&1
wait "$imu"
sleep 2  # the matcher's last scans and the ground station's last poses (a bench, not a test)
kill -INT "$matcher" && wait "$matcher" || true
kill -INT "$station" && wait "$station" || true
cat "$out"/lidar_driver.log "$out"/imu_bridge.log "$out"/slam_matcher.log

python3 - "$log" "$out/ground_station/trajectory.tum" "$out/estimate.txt" <<'PY'
import math, sys
log, tum, estimate = sys.argv[1:4]
# io::CarmenTimeline: max(last + 1e-4, ipc) after the first scan.
ipc_of, last, adjusted = {}, None, 0
for line in open(log):
    f = line.split()
    if not f or f[0] not in ("FLASER", "ROBOTLASER1"):
        continue
    ipc = float(f[-3])
    stamp = ipc if last is None else max(last + 1e-4, ipc)
    adjusted += stamp != ipc
    last = stamp
    ipc_of[round(stamp, 6)] = ipc
poses = unmapped = 0
with open(estimate, "w") as out:
    for line in open(tum):
        if line.startswith("#"):
            continue
        t, x, y, z, qx, qy, qz, qw = map(float, line.split())
        ipc = ipc_of.get(round(t, 6))
        if ipc is None:
            unmapped += 1
            continue
        theta = math.atan2(2 * (qw * qz + qx * qy), 1 - 2 * (qy * qy + qz * qz))
        out.write(f"{ipc:.6f} {x:.6f} {y:.6f} {theta:.6f}\n")
        poses += 1
print(f"{poses} poses written to {estimate} ({adjusted} scans of the log have an adjusted "
      f"timeline stamp; {unmapped} poses matched no scan)")
PY
"$bin/uavslam" eval --relations "$relations" --estimate "$out/estimate.txt"
