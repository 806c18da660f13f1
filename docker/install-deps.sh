#!/usr/bin/env bash
# The one list of uavslam's system dependencies (Debian 12 "bookworm" packages).
# Used by the Makefile (`make demo`, `make test`), .ci/run and docker/Dockerfile.
# Idempotent: installs only what is missing, so repeated runs cost a dpkg query.
set -euo pipefail

PACKAGES=(
  # build
  build-essential cmake ninja-build ccache pkg-config git
  # algorithm core
  libeigen3-dev libflann-dev liblz4-dev liboctomap-dev
  # recording (MCAP CRC-32)
  zlib1g-dev
  # DDS (Fast DDS 2.9, Fast CDR 1.0, fastddsgen 2.3, fastdds shm clean)
  libfastrtps-dev libfastcdr-dev fastddsgen fastdds-tools
  # config, command line, output
  libyaml-cpp-dev libcli11-dev nlohmann-json3-dev libpng-dev
  # tests and benchmarks; clang's libFuzzer for the log readers (make fuzz); clang-format (make format-check)
  libgtest-dev libgmock-dev libbenchmark-dev clang libclang-rt-14-dev clang-format
  # the benchmark tables (make bench, make real-logs)
  python3
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'ok installed' || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "install-deps: need root (or sudo) to install: ${missing[*]}" >&2; exit 1; }
  SUDO=sudo
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
