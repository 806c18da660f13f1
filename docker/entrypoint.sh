#!/usr/bin/env bash
# The image's entrypoint: runs one uavslam process as docker-compose.yml gives it,
#
#   uavslam-entrypoint PROCESS [ARGS...]
#
# - `{start_at}` in ARGS (as in config/launch/*.yaml) becomes the simulated sensors' shared start
#   time: $UAVSLAM_START_AT if set, else a time both sensor containers agree on through the file
#   $UAVSLAM_START_AT_FILE: the first to come writes now + $UAVSLAM_START_DELAY_S (5 s), the other
#   reads it (a file older than a minute is an earlier run's and is replaced).
# - With $UAVSLAM_LOG_DIR set, the output also goes to $UAVSLAM_LOG_DIR/PROCESS.log.
# The process replaces this script (exec), so it receives the container's SIGTERM itself.
set -euo pipefail

shared_start_at() {
  if [ -n "${UAVSLAM_START_AT:-}" ]; then
    echo "$UAVSLAM_START_AT"
    return
  fi
  local file=${UAVSLAM_START_AT_FILE:?"{start_at} needs UAVSLAM_START_AT or UAVSLAM_START_AT_FILE"}
  mkdir -p "$(dirname "$file")"
  (
    flock 9
    if [ -z "$(find "$file" -newermt '60 seconds ago' 2>/dev/null)" ]; then
      echo $(($(date +%s) + ${UAVSLAM_START_DELAY_S:-5})) >"$file"
    fi
    cat "$file"
  ) 9>"$file.lock"
}

[ $# -ge 1 ] || { echo "usage: uavslam-entrypoint PROCESS [ARGS...]" >&2; exit 2; }
args=()
for arg in "$@"; do
  if [ "$arg" = "{start_at}" ]; then
    arg=$(shared_start_at)
  fi
  args+=("$arg")
done

if [ -n "${UAVSLAM_LOG_DIR:-}" ]; then
  mkdir -p "$UAVSLAM_LOG_DIR"
  exec > >(tee -a "$UAVSLAM_LOG_DIR/$(basename "$1").log") 2>&1
fi
exec "${args[@]}"
