#!/usr/bin/env bash
# Makes the Docker sandbox of the build service usable on this machine:
#   1. starts dockerd when no engine answers (local socket only; with DOCKER_HOST set, the remote
#      engine is used as it is and nothing is started),
#   2. makes sure the image `contract-gcc` ($CONTRACT_IMAGE) exists and was built from the current
#      runtime sources, with runtime/docker/build-image-offline.sh: the one way to make it (it does
#      nothing when the image is up to date, else debootstrap + the runtime built inside + docker import).
# Prints "dockerd-started <pid>" when it started the daemon.
# Options: --rebuild (re-create the image), --daemon (step 1 only), --lease PID-TAG (the caller
# uses the engine until `--release PID-TAG` or until process PID ends), --release PID-TAG.
# A daemon this script started for a lease is stopped when its last lease is released or its
# last holder process is gone (a test file run alone, killed or not; `make test`'s run holds one
# lease for all its files, so one file never stops the engine under the others): a small watcher
# started with the daemon (--reap) checks the holders every 2 s and ends with the daemon. A
# daemon it did not start, or started without a lease (by hand), is never stopped.
# Two calls at once (test files of two suites) run one after the other (a lock file), so that
# neither starts a second daemon nor builds the image beside the other.
set -euo pipefail
self=$(cd "$(dirname "$0")" && pwd)/$(basename "$0")
cd "$(dirname "$0")/.."
IMAGE=${CONTRACT_IMAGE:-contract-gcc}
log() { printf '[docker-up] %s\n' "$*" >&2; }

users=${TMPDIR:-/tmp}/contract-docker-users   # leases/<PID-TAG>, started (the daemon's pid)
mkdir -p "$users/leases"
is_dockerd() { [ -r "/proc/$1/cmdline" ] && tr '\0' ' ' <"/proc/$1/cmdline" | grep -q '^dockerd '; }
lease_lock() { exec 8>"$users/lock"; flock 8; }
# drops the leases whose holder process is gone
prune_leases() {
  local l
  for l in "$users"/leases/*; do
    [ -e "$l" ] || continue
    name=${l##*/}
    [ -d "/proc/${name%%-*}" ] || rm -f "$l"
  done
}
# with the lease lock held: stops the daemon this script started when no lease is left
stop_when_unused() {
  prune_leases
  compgen -G "$users/leases/*" >/dev/null && return 0
  [ -f "$users/started" ] || return 0
  local pid; pid=$(cat "$users/started")
  rm -f "$users/started"
  is_dockerd "$pid" || return 0
  kill "$pid"
  for _ in $(seq 1 150); do [ -d "/proc/$pid" ] || { echo "dockerd-stopped $pid"; return 0; }; sleep 0.2; done
  log "dockerd $pid did not stop in 30 s"
  return 1
}

case "${1:-}" in
  --release)
    name=${2:?--release needs the lease name given to --lease}
    lease_lock
    rm -f "$users/leases/$name"
    stop_when_unused
    exit $? ;;
  --reap)
    # the watcher of a daemon started for a lease: stops it once every holder is gone
    pid=${2:?pid}
    while sleep 2; do
      lease_lock
      if [ "$(cat "$users/started" 2>/dev/null)" != "$pid" ] || ! is_dockerd "$pid"; then exit 0; fi
      stop_when_unused >/dev/null
      flock -u 8
    done ;;
esac
rebuild=0
daemon_only=0
lease=""
while [ $# -gt 0 ]; do
  case "$1" in
    --rebuild) rebuild=1 ;;
    --daemon) daemon_only=1 ;;
    --lease) lease=${2:?--lease needs PID-TAG}; shift
      [[ $lease =~ ^[0-9]+-[A-Za-z0-9_.-]+$ ]] || { log "--lease $lease: give PID-TAG (the holder's pid, a word)"; exit 2; } ;;
    *) log "unknown option $1"; exit 2 ;;
  esac
  shift
done

exec 9>"${TMPDIR:-/tmp}/contract-docker-up.lock"
flock 9

command -v docker >/dev/null || { log "the docker CLI is missing: apt-get install docker.io"; exit 1; }

# the engine's check, start and lease in one step under the lease lock: a release meanwhile cannot
# stop the engine this call found answering before its lease is taken
lease_lock
if ! docker info >/dev/null 2>&1; then
  if [ -n "${DOCKER_HOST:-}" ]; then
    log "no Docker engine answers at DOCKER_HOST=$DOCKER_HOST"
    exit 1
  fi
  command -v dockerd >/dev/null || { log "dockerd is missing: apt-get install docker.io"; exit 1; }
  [ "$(id -u)" = 0 ] || { log "starting dockerd needs root"; exit 1; }
  log "starting dockerd (no bridge, no iptables: sandbox containers have no network anyway)"
  mkdir -p /var/log
  nohup dockerd --host unix:///var/run/docker.sock --bridge=none --iptables=false --ip6tables=false \
    >/var/log/contract-dockerd.log 2>&1 8>&- 9>&- &  # the daemon must not hold the locks (fd 8, 9)
  pid=$!
  for _ in $(seq 1 100); do docker info >/dev/null 2>&1 && break; sleep 0.3; done
  if ! docker info >/dev/null 2>&1; then
    log "dockerd did not come up; last lines of /var/log/contract-dockerd.log:"
    tail -5 /var/log/contract-dockerd.log >&2
    kill "$pid" 2>/dev/null || true
    exit 1
  fi
  echo "dockerd-started $pid"
  if [ -n "$lease" ]; then
    echo "$pid" >"$users/started"
    setsid nohup bash "$self" --reap "$pid" </dev/null >/dev/null 2>&1 8>&- 9>&- &
  fi
fi
[ -n "$lease" ] && : >"$users/leases/$lease"
flock -u 8

[ $daemon_only = 1 ] && exit 0

build=(bash runtime/docker/build-image-offline.sh --image "$IMAGE")
[ $rebuild = 1 ] && build+=(--force)
"${build[@]}" >&2 || { log "runtime/docker/build-image-offline.sh could not make the image $IMAGE"; exit 1; }
