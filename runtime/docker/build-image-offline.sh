#!/usr/bin/env bash
# Produces the `contract-gcc` Docker image without pulling anything from a Docker registry
# (the one way to make it: scripts/docker-up.sh calls this script):
#   debootstrap --variant=minbase --include=gcc,make,libc6-dev bookworm ROOT <mirror of this host>
#   + the runtime sources copied to ROOT/opt/contract/runtime, built and installed there (chroot)
#   + its C tests run inside the chroot (skip with --no-test)
#   | tar | docker import - contract-gcc
# Same content as runtime/docker/Dockerfile. Idempotent: does nothing when the image exists
# (and, if it carries the label contract.runtime-sources, was built from the current runtime
# sources), unless --force. Needs root (debootstrap, chroot) and a running Docker engine.
# Options: --force  --no-test  --image NAME (default $CONTRACT_IMAGE or contract-gcc)
#          --mirror URL (default: the first Debian URI of /etc/apt/sources.list[.d])
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
runtime_dir=$(cd "$here/.." && pwd)
IMAGE=${CONTRACT_IMAGE:-contract-gcc}
force=0; run_tests=1; mirror=""
log() { printf '[build-image] %s\n' "$*" >&2; }
die() { log "error: $*"; exit 1; }

while [ $# -gt 0 ]; do
  case "$1" in
    --force) force=1 ;;
    --no-test) run_tests=0 ;;
    --image) IMAGE=${2:?--image needs a name}; shift ;;
    --mirror) mirror=${2:?--mirror needs a URL}; shift ;;
    -h|--help) sed -n '2,12p' "$0"; exit 0 ;;
    *) die "unknown option $1 (see --help)" ;;
  esac
  shift
done

command -v docker >/dev/null || die "the docker CLI is missing"
docker info >/dev/null 2>&1 || die "no Docker engine answers (start dockerd first)"
# fingerprint of the runtime sources, kept as the image's label: an image built from other sources is
# rebuilt. The tests and benchmarks (tests/, bench/) are not in it: the jobs use the library, the
# launcher and the headers, and a change of a test alone does not cost a rebuild
runtime_hash=$(cd "$runtime_dir" && find . \( -path ./build -o -path ./tests -o -path ./bench \) -prune -o -type f \( -name '*.c' -o -name '*.h' -o -name '*.mk' -o -name Makefile -o -name '*.def' \) -print \
  | LC_ALL=C sort | xargs sha256sum | sha256sum | cut -c1-16)

if [ $force = 0 ] && docker image inspect "$IMAGE" >/dev/null 2>&1; then
  label=$(docker image inspect -f '{{ index .Config.Labels "contract.runtime-sources" }}' "$IMAGE" 2>/dev/null || true)
  if [ -z "$label" ] || [ "$label" = "<no value>" ] || [ "$label" = "$runtime_hash" ]; then
    log "image $IMAGE already exists: nothing to do (use --force to rebuild it)"
    exit 0
  fi
  log "image $IMAGE was built from other runtime sources ($label, now $runtime_hash): rebuilding"
fi
[ "$(id -u)" = 0 ] || die "debootstrap and chroot need root"
command -v debootstrap >/dev/null || die "debootstrap is missing (apt-get install debootstrap)"

if [ -z "$mirror" ]; then
  mirror=$(cat /etc/apt/sources.list.d/*.sources 2>/dev/null | awk '/^URIs:/ {print $2}' | grep -v security | head -1 || true)
  [ -n "$mirror" ] || mirror=$(awk '$1 == "deb" && $0 !~ /security/ {print $2; exit}' /etc/apt/sources.list 2>/dev/null || true)
  [ -n "$mirror" ] || mirror=http://deb.debian.org/debian
fi

work=$(mktemp -d /tmp/contract-rootfs-XXXXXX)
root="$work/root"
cleanup() {
  mountpoint -q "$root/proc" 2>/dev/null && umount "$root/proc" || true
  rm -rf "$work"
}
trap cleanup EXIT

log "debootstrap bookworm from $mirror into $root"
debootstrap --variant=minbase --include=gcc,make,libc6-dev bookworm "$root" "$mirror" >"$work/debootstrap.log" 2>&1 \
  || { tail -20 "$work/debootstrap.log" >&2; die "debootstrap failed (log above)"; }

log "copying the runtime sources to /opt/contract/runtime"
mkdir -p "$root/opt/contract/runtime"
tar -C "$runtime_dir" --exclude=./build -c . | tar -C "$root/opt/contract/runtime" -x

log "building and installing the runtime inside the image"
mount -t proc proc "$root/proc"
chroot "$root" /bin/sh -c 'cd /opt/contract/runtime && make -s clean && make -s -j2 all && make -s install PREFIX=/opt/contract/runtime' \
  || die "building the runtime inside the image failed"
if [ $run_tests = 1 ]; then
  log "running the runtime's C tests inside the image"
  chroot "$root" /bin/sh -c 'cd /opt/contract/runtime && make -s test-c' >"$work/tests.log" 2>&1 \
    || { tail -30 "$work/tests.log" >&2; die "the runtime tests failed inside the image"; }
  tail -1 "$work/tests.log" >&2
fi
umount "$root/proc"
# build/obj stays (generated Makefiles ask make for build/libmodule.a: it must be up to date)
rm -rf "$root/opt/contract/runtime/build/tests" \
       "$root/opt/contract/runtime/build/san" "$root/opt/contract/runtime/build/bench" \
       "$root/var/cache/apt/archives/"*.deb "$root/var/lib/apt/lists/"* 2>/dev/null || true
mkdir -p "$root/work"

log "importing $IMAGE"
old_id=$(docker image inspect -f '{{.Id}}' "$IMAGE" 2>/dev/null || true)
tar -C "$root" -c . | docker import \
  --change 'ENV PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin' \
  --change 'ENV CONTRACT_RUNTIME=/opt/contract/runtime' \
  --change 'WORKDIR /work' \
  --change "LABEL contract.runtime-sources=$runtime_hash" \
  --change 'CMD ["/bin/bash"]' \
  - "$IMAGE" >/dev/null
# the image it replaces (now untagged) would stay behind, ~330 MB each time the runtime changes
if [ -n "$old_id" ] && [ "$old_id" != "$(docker image inspect -f '{{.Id}}' "$IMAGE")" ]; then
  docker image rm "$old_id" >/dev/null 2>&1 && log "removed the image it replaces (${old_id#sha256:})" \
    || log "the image it replaces (${old_id#sha256:}) is still in use: left in place"
fi
log "image $IMAGE ready ($(docker image inspect -f '{{.Size}}' "$IMAGE" | awk '{printf "%.0f MB", $1/1e6}'))"
