#!/usr/bin/env bash
# Makes the Docker sandbox of the build service usable on this machine:
#   1. starts dockerd when no engine answers (local socket only; with DOCKER_HOST set, the remote
#      engine is used as it is and nothing is started),
#   2. makes sure the image `contract-gcc` ($CONTRACT_IMAGE) exists and was built from the current
#      runtime sources, with runtime/docker/build-image-offline.sh: the one way to make it (it does
#      nothing when the image is up to date, else debootstrap + the runtime built inside + docker import).
# Prints "dockerd-started <pid>" when it started the daemon (the caller may stop it afterwards).
# Options: --rebuild (re-create the image), --daemon (step 1 only), --stop <pid> (stop a daemon
# this script started). Two calls at once (test files of two suites) run one after the other
# (a lock file), so that neither starts a second daemon nor builds the image beside the other.
set -euo pipefail
cd "$(dirname "$0")/.."
IMAGE=${CONTRACT_IMAGE:-contract-gcc}
log() { printf '[docker-up] %s\n' "$*" >&2; }

if [ "${1:-}" = "--stop" ]; then
  pid=${2:?pid}
  if [ -r "/proc/$pid/cmdline" ] && tr '\0' ' ' <"/proc/$pid/cmdline" | grep -q '^dockerd '; then
    kill "$pid"
    for _ in $(seq 1 50); do [ -d "/proc/$pid" ] || exit 0; sleep 0.2; done
    log "dockerd $pid did not stop in 10 s"
    exit 1
  fi
  exit 0
fi
rebuild=0
daemon_only=0
[ "${1:-}" = "--rebuild" ] && rebuild=1
[ "${1:-}" = "--daemon" ] && daemon_only=1

exec 9>"${TMPDIR:-/tmp}/contract-docker-up.lock"
flock 9

command -v docker >/dev/null || { log "the docker CLI is missing: apt-get install docker.io"; exit 1; }

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
    >/var/log/contract-dockerd.log 2>&1 9>&- &  # the daemon must not hold the lock (fd 9)
  pid=$!
  for _ in $(seq 1 100); do docker info >/dev/null 2>&1 && break; sleep 0.3; done
  if ! docker info >/dev/null 2>&1; then
    log "dockerd did not come up; last lines of /var/log/contract-dockerd.log:"
    tail -5 /var/log/contract-dockerd.log >&2
    kill "$pid" 2>/dev/null || true
    exit 1
  fi
  echo "dockerd-started $pid"
fi

[ $daemon_only = 1 ] && exit 0

build=(bash runtime/docker/build-image-offline.sh --image "$IMAGE")
[ $rebuild = 1 ] && build+=(--force)
"${build[@]}" >&2 || { log "runtime/docker/build-image-offline.sh could not make the image $IMAGE"; exit 1; }
