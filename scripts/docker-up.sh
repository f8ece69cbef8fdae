#!/usr/bin/env bash
# Makes the Docker sandbox of the build service usable on this machine:
#   1. starts dockerd when no engine answers (local socket only; with DOCKER_HOST set, the remote
#      engine is used as it is and nothing is started),
#   2. makes sure the image `contract-gcc` exists: built by runtime/docker/build-image-offline.sh
#      when the runtime provides it, otherwise bootstrapped here, offline, from the host's own
#      Debian packages (gcc, make, libc headers ... listed by dpkg) plus the runtime built at
#      /opt/contract/runtime, then `docker import`ed.
# Prints "dockerd-started <pid>" when it started the daemon (the caller may stop it afterwards).
# Options: --rebuild (re-create the image), --stop <pid> (stop a daemon this script started).
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
[ "${1:-}" = "--rebuild" ] && rebuild=1

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
    >/var/log/contract-dockerd.log 2>&1 &
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

# fingerprint of the runtime sources: an image bootstrapped here from older sources is rebuilt
runtime_hash=$(cd runtime && find . -path ./build -prune -o -type f \( -name '*.c' -o -name '*.h' -o -name '*.mk' -o -name Makefile -o -name '*.def' \) -print \
  | LC_ALL=C sort | xargs sha256sum | sha256sum | cut -c1-16)
if [ $rebuild = 0 ] && docker image inspect "$IMAGE" >/dev/null 2>&1; then
  label=$(docker image inspect -f '{{ index .Config.Labels "contract.runtime-sources" }}' "$IMAGE" 2>/dev/null || true)
  if [ -z "$label" ] || [ "$label" = "<no value>" ] || [ "$label" = "$runtime_hash" ]; then
    log "image $IMAGE present"
    exit 0
  fi
  log "image $IMAGE was bootstrapped from other runtime sources ($label, now $runtime_hash): rebuilding"
fi

if [ -x runtime/docker/build-image-offline.sh ]; then
  log "building $IMAGE with runtime/docker/build-image-offline.sh"
  runtime/docker/build-image-offline.sh >&2
  docker image inspect "$IMAGE" >/dev/null 2>&1 && exit 0
  log "runtime/docker/build-image-offline.sh did not produce $IMAGE; bootstrapping here"
fi

log "bootstrapping $IMAGE offline from the host's packages"
work=$(mktemp -d /tmp/contract-image-XXXXXX)
trap 'rm -rf "$work"' EXIT
pkgs=$(apt-cache depends --recurse --no-recommends --no-suggests --no-conflicts --no-breaks \
  --no-replaces --no-enhances --installed \
  gcc make libc6-dev coreutils dash bash grep sed findutils mawk diffutils libc-bin base-files procps \
  2>/dev/null | grep -v '^ ' | grep -v '^<' | sort -u)
: >"$work/files"
for p in $pkgs; do dpkg -L "$p" 2>/dev/null >>"$work/files" || true; done
# the dynamic loader links of a usr-merged system and the runtime, then a minimal /etc
root="$work/root"
mkdir -p "$root/etc" "$root/tmp" "$root/work" "$root/opt/contract"
chmod 1777 "$root/tmp"
printf 'root:x:0:0:root:/root:/bin/sh\ncontract:x:1000:1000:contract:/work:/bin/sh\n' >"$root/etc/passwd"
printf 'root:x:0:\ncontract:x:1000:\n' >"$root/etc/group"
log "building the runtime for /opt/contract/runtime"
mkdir -p "$root/opt/contract/runtime"
tar -C runtime --exclude=./build --exclude='*.csv' --exclude='*.o' -cf - . | tar -C "$root/opt/contract/runtime" -xf -
make -s -C "$root/opt/contract/runtime" >&2
# usr-merged hosts: /lib, /bin, /sbin, /lib64 are links into /usr, dpkg still lists the old paths
while read -r f; do
  case "$f" in
    /lib/*|/bin/*|/sbin/*|/lib64/*) top=${f#/}; top=/${top%%/*}; [ -L "$top" ] && f=/usr$f ;;
  esac
  printf '%s\n' "$f"
done <"$work/files" | sort -u | while read -r f; do
  [ -e "$f" ] || [ -L "$f" ] || continue
  [ -d "$f" ] && [ ! -L "$f" ] && continue
  printf '%s\n' "${f#/}"
done >"$work/list"
for l in bin sbin lib lib64; do [ -L "/$l" ] && printf '%s\n' "$l" >>"$work/list"; done
[ -e /etc/ld.so.cache ] && printf 'etc/ld.so.cache\n' >>"$work/list"
for a in /etc/alternatives/*; do [ -L "$a" ] && printf '%s\n' "${a#/}" >>"$work/list"; done
for b in cc c89 c99 cpp awk; do [ -L "/usr/bin/$b" ] && printf 'usr/bin/%s\n' "$b" >>"$work/list"; done
(
  tar -C / --no-recursion -cf "$work/host.tar" -T "$work/list" 2>/dev/null || true
  mkdir -p "$root" && tar -C "$root" -xf "$work/host.tar"
)
chown 1000:1000 "$root/work"
tar -C "$root" --numeric-owner -cf - . | docker import \
  --change 'USER 1000:1000' --change 'WORKDIR /work' --change 'ENV PATH=/usr/local/bin:/usr/bin:/bin' \
  --change 'ENV CONTRACT_RUNTIME=/opt/contract/runtime' \
  --change "LABEL contract.runtime-sources=$runtime_hash" - "$IMAGE" >&2
docker run --rm --network none "$IMAGE" sh -c 'gcc --version | head -1 && make --version | head -1 && ls /opt/contract/runtime/build' >&2
log "image $IMAGE ready"
