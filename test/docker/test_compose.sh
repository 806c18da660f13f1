#!/usr/bin/env bash
# ctest `docker_compose` (label docker): docker/docker-compose.yml and its ground override are valid
# Compose files (`docker-compose config -q`), and, where Podman can run containers here, the image
# builds (docker/Dockerfile) and the compose demo flies 20 s of the demo flight to its end on DDS
# domain 210 (the host's network and IPC namespaces, loopback-only participant profile), after
# which the outputs are checked: every container exited 0, the ground station's files written on
# SIGTERM, poses and map received, ATE < 0.1 m, a complete recording, logs, all owned by the
# image's non-root user.
#
#   test_compose.sh SOURCE_DIR BIN_DIR     (BIN_DIR: the host build's bin/, for eval and --dump)
#
# Exit 0 passed, 1 failed, 77 skipped (no Podman/docker-compose, not root, or no container runs:
# the reason is printed). Podman's state for the test (containers.conf, API socket) lives in a
# temporary folder removed at the end; the image and Podman's build cache (ccache) stay in
# Podman's storage, so later runs rebuild only what changed.
set -euo pipefail

SRC=$(cd "$1" && pwd)
BIN=$(cd "$2" && pwd)
SKIPPED=77
DOMAIN=210
DURATION=20

skip() {
  echo "SKIPPED: $*"
  exit "$SKIPPED"
}
fail() {
  echo "FAILED: $*" >&2
  exit 1
}
seconds_since() { echo $(($(date +%s) - $1)); }

command -v docker-compose >/dev/null || skip "docker-compose is not installed (docker/install-deps.sh installs it)"
for file in docker-compose.yml "docker-compose.yml -f $SRC/docker/docker-compose.ground.yml"; do
  # shellcheck disable=SC2086
  docker-compose -f "$SRC/docker/"$file config -q || fail "docker-compose config rejects docker/$file"
done
echo "docker-compose config: docker-compose.yml and docker-compose.ground.yml are valid"

command -v podman >/dev/null || skip "podman is not installed (docker/install-deps.sh installs it)"
[ "$(id -u)" -eq 0 ] || skip "the container run needs root (rootful Podman)"

WORK=$(mktemp -d /tmp/uavslam-docker.XXXXXX)
PROJECT=uavslam-test-$$
SERVICE_PID=""
compose() {
  DOCKER_HOST=unix://$WORK/podman.sock COMPOSE_PROJECT_NAME=$PROJECT UAVSLAM_OUT=$WORK/out UAVSLAM_RUN=demo \
    UAVSLAM_DURATION=$DURATION UAVSLAM_DOMAIN=$DOMAIN UAVSLAM_UID=1000 UAVSLAM_GID=1000 \
    docker-compose -f "$SRC/docker/docker-compose.yml" "$@"
}
cleanup() {
  if [ -n "$SERVICE_PID" ]; then
    compose down -t 5 >/dev/null 2>&1 || true
    kill "$SERVICE_PID" 2>/dev/null || true
    wait "$SERVICE_PID" 2>/dev/null || true
  fi
  fastdds shm clean >/dev/null 2>&1 || true
  rm -rf "$WORK"
}
trap cleanup EXIT
trap 'exit 1' INT TERM  # ctest's timeout: still clean up

export CONTAINERS_CONF=$WORK/containers.conf
cat >"$CONTAINERS_CONF" <<'CONF'
[containers]
default_ulimits = ["nofile=20000:20000", "nproc=32768:32768"]
[engine]
runtime = "runc"
cgroup_manager = "cgroupfs"
events_logger = "file"
CONF

start=$(date +%s)
"$SRC/docker/import-base-image.sh" || skip "no debian:bookworm base image (docker/import-base-image.sh failed)"
echo "base image: $(seconds_since "$start") s"
if ! probe=$(podman run --rm --network host --ipc host debian:bookworm true 2>&1); then
  skip "podman cannot run a container here: $probe"
fi

podman system service --time=0 "unix://$WORK/podman.sock" >"$WORK/podman-service.log" 2>&1 &
SERVICE_PID=$!
for _ in $(seq 100); do
  [ -S "$WORK/podman.sock" ] && break
  sleep 0.1
done
[ -S "$WORK/podman.sock" ] || fail "podman system service did not open its socket: $(cat "$WORK/podman-service.log")"

start=$(date +%s)
compose build >"$WORK/build.log" 2>&1 || { tail -40 "$WORK/build.log"; fail "the image build failed"; }
grep -E '^ *(Hits|Misses)' "$WORK/build.log" | sed 's/^/  ccache /' || true
echo "image build: $(seconds_since "$start") s"

# The out folder belongs to the image's user (uid 1000), as a user's own folder would.
mkdir -p "$WORK/out"
chown 1000:1000 "$WORK/out"
start=$(date +%s)
status=0
compose up --abort-on-container-exit --exit-code-from lidar_driver -t 30 >"$WORK/up.log" 2>&1 || status=$?
echo "compose demo: $(seconds_since "$start") s (${DURATION} s flight), lidar_driver exit code $status"
for container in $(compose ps -q); do
  podman inspect -f '{{.Name}} {{.State.ExitCode}}' "$container"
done | tee "$WORK/exit_codes"
RUN=$WORK/out/demo
if [ "$status" -ne 0 ] || awk '$2 != 0 {bad = 1} END {exit !bad}' "$WORK/exit_codes"; then
  tail -60 "$WORK/up.log"
  fail "a container exited non-zero (above)"
fi
[ "$(wc -l <"$WORK/exit_codes")" -eq 6 ] || fail "expected 6 containers, got: $(cat "$WORK/exit_codes")"

for file in trajectory.tum map.bt map_occupied.ply map_topdown.png summary.json; do
  [ -s "$RUN/ground_station/$file" ] || fail "the ground station did not write $file on stop"
done
for name in ground_station map_server recorder slam_matcher imu_bridge lidar_driver; do
  [ -s "$RUN/logs/$name.log" ] || fail "no log $RUN/logs/$name.log"
done
[ -s "$RUN/map_server/map.bt" ] || fail "the map server did not write map.bt"
foreign=$(find "$RUN" ! -uid 1000 -print)
[ -z "$foreign" ] || fail "files not owned by the image's user (uid 1000): $foreign"

"$BIN/recorder" --dump "$RUN/recording_000.mcap" >"$WORK/dump.txt" || { cat "$WORK/dump.txt"; fail "recording not complete"; }
"$BIN/uavslam" eval --estimate "$RUN/ground_station/trajectory.tum" --groundtruth "$RUN/groundtruth.tum" \
  --json >"$WORK/eval.json" || fail "uavslam eval failed"
"$BIN/uavslam" report "$RUN" || fail "uavslam report failed"
python3 - "$RUN" "$WORK/eval.json" <<'CHECK' || fail "the ground station's outputs are wrong (above)"
import json, sys
run, eval_path = sys.argv[1], sys.argv[2]
summary = json.load(open(f"{run}/ground_station/summary.json"))
published = sum(1 for line in open(f"{run}/groundtruth.tum") if line.strip() and not line.startswith("#"))
status, poses, mp = summary["matcher_status"], summary["poses"], summary["map"]
ate = json.load(open(eval_path))["ate_rmse_m"]
checks = [
    (published >= 0.95 * 40 * 20, f"{published} scans published, expected about 800"),
    (status["scans_received"] >= 0.95 * published, f"matcher received {status['scans_received']} of {published} scans"),
    (poses["received"] >= 0.9 * published, f"ground station received {poses['received']} poses of {published} scans"),
    (mp["map_points"] > 0 and mp["occupied_cells"] > 0, f"ground station map: {mp}"),
    (ate < 0.1, f"ATE RMSE {ate:.4f} m >= 0.1 m"),
]
failed = [what for ok, what in checks if not ok]
for what in failed:
    print("  wrong:", what)
print(f"outputs: {published} scans, {status['scans_received']} received by the matcher, {poses['received']} poses, "
      f"map {mp['map_points']} points / {mp['occupied_cells']} cells, ATE {ate:.4f} m")
sys.exit(1 if failed else 0)
CHECK
echo "PASSED: the compose demo ran to its end and the ground station's outputs are right"
