#!/usr/bin/env bash
# The tables of docs/algorithm.md#what-the-scan-can-see: every shipped scenario flown with the seed
# (config/seed.yaml) and with the UAV's config (config/slam.yaml: IMU motion prior + degeneracy),
# then degeneracy.threshold swept on the scenarios and, with --real-logs, on the Freiburg logs
# (config/slam_2d_logs.yaml + the threshold, scored on their relations; with --jitter-runs N each
# log is also run N times under a 1e-6 rad heading perturbation, seeds 1..N, for the spread).
# Usage: test/bench/degeneracy_table.sh [--build-dir DIR] [--real-logs] [--jitter-runs N] [--data DIR]
set -euo pipefail

repo_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build_dir="${repo_dir}/build"
data_dir="${repo_dir}/../shared/data/freiburg"
real_logs=false
jitter_runs=0
while [[ $# -gt 0 ]]; do
  case "$1" in
    --build-dir) build_dir="$2"; shift 2 ;;
    --data) data_dir="$2"; shift 2 ;;
    --real-logs) real_logs=true; shift ;;
    --jitter-runs) jitter_runs="$2"; shift 2 ;;
    -h|--help) sed -n '2,7p' "$0"; exit 0 ;;
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

# A log's mean relation errors (m): "all under_5_s". $1 log, $2 threshold, then uavslam run options.
run_log() {
  local log="$1" threshold="$2"; shift 2
  local dir="${out_dir}/${log}"
  rm -rf "${dir}"
  "${uavslam}" run --quiet --carmen "${data_dir}/${log}.clf" --out "${dir}" \
    --config "${repo_dir}/config/slam_2d_logs.yaml" --set degeneracy.threshold="${threshold}" "$@" > /dev/null
  "${uavslam}" eval --json --relations "${data_dir}/${log}.relations" \
    --estimate "${dir}/estimate.txt" > "${dir}.json"
  python3 -c 'import json,sys; e=json.load(open(sys.argv[1])); print("%.4f %.4f" % (e["all"]["translation_m"]["mean"], e["short_span"]["translation_m"]["mean"]))' "${dir}.json"
}

echo
if [[ "${jitter_runs}" -gt 0 ]]; then
  echo "| degeneracy.threshold (config/slam_2d_logs.yaml) | intel: all, under 5 s (m); all over ${jitter_runs} perturbed runs: mean [min, max] | fr079 | aces |"
else
  echo "| degeneracy.threshold (config/slam_2d_logs.yaml) | intel: all, under 5 s (m) | fr079 | aces |"
fi
echo "|---|---|---|---|"
for t in 0 "${thresholds[@]}"; do
  row="| ${t} |"
  for log in intel fr079 aces; do
    echo "running ${log} at ${t} ..." >&2
    read -r all short < <(run_log "${log}" "${t}")
    cell="${all}, ${short}"
    if [[ "${jitter_runs}" -gt 0 ]]; then
      perturbed=()
      for seed in $(seq 1 "${jitter_runs}"); do
        read -r a _ < <(run_log "${log}" "${t}" --heading-jitter 1e-6 --jitter-seed "${seed}")
        perturbed+=("${a}")
      done
      cell+="; $(printf '%s\n' "${perturbed[@]}" | python3 -c 'import sys; v=[float(x) for x in sys.stdin]; print("%.4f [%.4f, %.4f]" % (sum(v)/len(v), min(v), max(v)))')"
    fi
    row+=" ${cell} |"
  done
  echo "${row}"
done
