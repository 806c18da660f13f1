#!/usr/bin/env bash
# Makes the image `debian:bookworm` that docker/Dockerfile starts FROM, for a Podman with no registry
# to pull it from: a minimal Debian 12 built by debootstrap from the machine's own Debian mirror,
# upgraded with bookworm-updates and bookworm-security, imported into Podman's storage (~80 s, once;
# needs root). Where a registry is reachable, `podman pull debian:bookworm` does the same.
#
#   docker/import-base-image.sh            # does nothing if the image exists
set -euo pipefail

IMAGE=localhost/debian:bookworm
if podman image exists "$IMAGE"; then
  exit 0
fi

# The mirror apt uses here (deb822 or one-line sources), so no other host is needed.
mirror=$({ grep -rhoE 'https?://[^ ]+/debian/?( |$)' /etc/apt/sources.list /etc/apt/sources.list.d/ 2>/dev/null || true; } |
  head -1 | tr -d ' ')
mirror=${mirror:-http://deb.debian.org/debian}
security=${mirror%/debian*}/debian-security

rootfs=$(mktemp -d /var/tmp/uavslam-rootfs.XXXXXX)
trap 'rm -rf "$rootfs"' EXIT
echo "import-base-image: debootstrap bookworm from $mirror"
debootstrap --variant=minbase bookworm "$rootfs" "$mirror" >"$rootfs.log" 2>&1 ||
  { tail -20 "$rootfs.log" >&2; rm -f "$rootfs.log"; exit 1; }
rm -f "$rootfs.log"
cat >"$rootfs/etc/apt/sources.list" <<SOURCES
deb $mirror bookworm main
deb $mirror bookworm-updates main
deb $security bookworm-security main
SOURCES
chroot "$rootfs" sh -c 'apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get -y -qq upgrade && apt-get clean' \
  >"$rootfs.log" 2>&1 || { tail -20 "$rootfs.log" >&2; rm -f "$rootfs.log"; exit 1; }
rm -f "$rootfs.log"
rm -rf "$rootfs"/var/lib/apt/lists/*
tar --numeric-owner -C "$rootfs" -c . | podman import --quiet - "$IMAGE" >/dev/null
podman tag "$IMAGE" docker.io/library/debian:bookworm
echo "import-base-image: $IMAGE (= debian:bookworm)"
