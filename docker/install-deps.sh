#!/usr/bin/env bash
# The one list of uavslam's system dependencies (Debian 12 "bookworm" packages).
# Used by the Makefile (`make demo`, `make test`), .ci/run and docker/Dockerfile.
# Idempotent: installs only what is missing, so repeated runs cost a dpkg query.
set -euo pipefail

# Compiling the project (also the image's build stage: docker/Dockerfile runs `install-deps.sh --build`).
BUILD_PACKAGES=(
  # build
  build-essential cmake ninja-build ccache pkg-config git
  # algorithm core
  libeigen3-dev libflann-dev liblz4-dev liboctomap-dev
  # the pose-graph back end (src/backend): Ceres 2.1
  libceres-dev
  # recording (MCAP CRC-32; lz4 and zstd chunk compression)
  zlib1g-dev libzstd-dev
  # DDS (Fast DDS 2.9, Fast CDR 1.0, fastddsgen 2.3, fastdds shm clean)
  libfastrtps-dev libfastcdr-dev fastddsgen fastdds-tools
  # config, command line, output
  libyaml-cpp-dev libcli11-dev nlohmann-json3-dev libpng-dev
  # GoogleTest: CMake requires it even when only the processes are built
  libgtest-dev libgmock-dev
)

# Only what the built processes link at run time, no dev packages (the image's runtime stage:
# `install-deps.sh --runtime`; `ldd build/bin/*` lists them).
RUNTIME_PACKAGES=(
  libfastrtps2.9 libfastcdr1 liboctomap1.9 libyaml-cpp0.7 libpng16-16 liblz4-1 zlib1g libzstd1 libceres3
)

# The rest of `make test` and `make bench` on the host (never in the image).
HOST_PACKAGES=(
  # tests and benchmarks; clang's libFuzzer for the log readers (make fuzz); clang-format (make format-check)
  libbenchmark-dev clang libclang-rt-14-dev clang-format
  # the benchmark tables (make bench, make real-logs)
  python3
  # the two-host link emulation tests (ctest -L twohost): NFQUEUE delay/loss tool, per-namespace rules
  libnetfilter-queue-dev iptables
  # the container test (ctest -L docker, test/docker/test_compose.sh): Podman with runc (apt would pick
  # crun, which fails on hybrid cgroups), docker-compose 1.29 against Podman's socket, debootstrap for
  # the base image (no registry is reachable)
  podman runc docker-compose debootstrap
)

case "${1:-}" in
  "") PACKAGES=("${BUILD_PACKAGES[@]}" "${HOST_PACKAGES[@]}") ;;
  --build) PACKAGES=("${BUILD_PACKAGES[@]}") ;;
  --runtime) PACKAGES=("${RUNTIME_PACKAGES[@]}") ;;
  *) echo "usage: install-deps.sh [--build | --runtime]  (no option: everything the host needs)" >&2; exit 2 ;;
esac

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
