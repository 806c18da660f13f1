#!/usr/bin/env bash
# The tables of docs/algorithm.md#what-the-scan-can-see: every shipped scenario flown with the seed
# (config/seed.yaml) and with the UAV's config (config/slam.yaml: IMU motion prior + degeneracy),
# then degeneracy.threshold swept on the scenarios and, with --real-logs, on the Freiburg logs
# (config/slam_2d_logs.yaml + the threshold, scored on their relations).
# Usage: test/bench/degeneracy_table.sh [--build-dir DIR] [--real-logs] [--data DIR]
set -euo pipefail

repo_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build_dir="${repo_dir}/build"
data_dir="${repo_dir}/../shared/data/freiburg"
real_logs=false
while [[ $# -gt 0 ]]; do
  case "$1" in
    --build-dir) build_dir="$2"; shift 2 ;;
    --data) data_dir="$2"; shift 2 ;;
    --real-logs) real_logs=true; shift ;;
    -h|--help) sed -n '2,6p' "$0"; exit 0 ;;
    *) echo "degeneracy_table.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
uavslam="${build_dir}/bin/uavslam"
[[ -x "${uavslam}" ]] || { echo "degeneracy_table.sh: ${uavslam} not built (make build)" >&2; exit 2; }
out_dir="$(mktemp -d)"
trap 'rm -rf "${out_dir}"' EXIT
scenarios=(demo short yaw_drift corridor plain_corridor)

# ATE horizontal RMSE (m) and the share of accepted scans with a degenerate direction.
fly() {
  local scenario="$1" config="$2"; shift 2
  local dir="${out_dir}/fly"
  rm -rf "${dir}"
  "${uavslam}" simulate --quiet --scenario "${repo_dir}/config/scenarios/${scenario}.yaml" \
    --config "${repo_dir}/${config}" --out "${dir}" "$@" > /dev/null
  python3 - "${dir}" <<'PY'
import csv, json, sys
s = json.load(open(sys.argv[1] + "/summary.json"))
rows = [r for r in csv.DictReader(open(sys.argv[1] + "/scans.csv")) if r["outcome"] == "accepted"]
flagged = sum(1 for r in rows if int(r["degenerate"]) > 0)
print("%.3f m (%d %%)" % (s["trajectory_errors"]["ate_horizontal_rmse_m"], round(100.0 * flagged / max(1, len(rows)))))
PY
}

echo "| scenario | seed (config/seed.yaml) | UAV (config/slam.yaml) |"
echo "|---|---|---|"
for s in "${scenarios[@]}"; do
  echo "running ${s} ..." >&2
  echo "| ${s} | $(fly "${s}" config/seed.yaml) | $(fly "${s}" config/slam.yaml) |"
done

thresholds=(0.02 0.05 0.1)
echo
echo "| degeneracy.threshold (config/slam.yaml) | $(printf '%s | ' "${scenarios[@]}")"
echo "|---|$(printf -- '---|%.0s' "${scenarios[@]}")"
for t in "${thresholds[@]}"; do
  row="| ${t} |"
  for s in "${scenarios[@]}"; do row+=" $(fly "${s}" config/slam.yaml --set degeneracy.threshold="${t}") |"; done
  echo "${row}"
done

${real_logs} || exit 0
echo
echo "| degeneracy.threshold (config/slam_2d_logs.yaml) | intel: all, under 5 s (m) | fr079 | aces |"
echo "|---|---|---|---|"
for t in 0 "${thresholds[@]}"; do
  row="| ${t} |"
  for log in intel fr079 aces; do
    echo "running ${log} at ${t} ..." >&2
    dir="${out_dir}/${log}"
    rm -rf "${dir}"
    "${uavslam}" run --quiet --carmen "${data_dir}/${log}.clf" --out "${dir}" \
      --config "${repo_dir}/config/slam_2d_logs.yaml" --set degeneracy.threshold="${t}" > /dev/null
    "${uavslam}" eval --json --relations "${data_dir}/${log}.relations" \
      --estimate "${dir}/estimate.txt" > "${dir}.json"
    row+=" $(python3 -c 'import json,sys; e=json.load(open(sys.argv[1])); print("%.4f, %.4f" % (e["all"]["translation_m"]["mean"], e["short_span"]["translation_m"]["mean"]))' "${dir}.json") |"
  done
  echo "${row}"
done
