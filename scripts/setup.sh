#!/usr/bin/env bash
# One-time, idempotent set-up for a fresh clone on a fresh Debian/Ubuntu machine:
# system packages (bubblewrap, chromium, docker.io, debootstrap), npm dependencies,
# the Langium generated parser, TypeScript builds and the C runtime.
# Safe to run again: every step checks first and does nothing when already done.
set -euo pipefail
cd "$(dirname "$0")/.."

log() { printf '[setup] %s\n' "$*"; }

need_pkgs=()
command -v bwrap     >/dev/null 2>&1 || need_pkgs+=(bubblewrap)
command -v chromium  >/dev/null 2>&1 || need_pkgs+=(chromium)
command -v dockerd   >/dev/null 2>&1 || need_pkgs+=(docker.io)
command -v debootstrap >/dev/null 2>&1 || need_pkgs+=(debootstrap)
command -v gcc       >/dev/null 2>&1 || need_pkgs+=(gcc)
command -v make      >/dev/null 2>&1 || need_pkgs+=(make)
command -v unzip     >/dev/null 2>&1 || need_pkgs+=(unzip)   # packages/vscode test reads the .vsix
if [ ${#need_pkgs[@]} -gt 0 ]; then
  if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
    log "installing system packages: ${need_pkgs[*]}"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq >/dev/null
    apt-get install -y -qq "${need_pkgs[@]}" >/dev/null
  else
    log "WARNING: missing system packages (${need_pkgs[*]}) and no root apt-get: install them yourself"
  fi
fi

if [ ! -d node_modules ] || [ package-lock.json -nt node_modules/.package-lock.json ]; then
  log "npm ci (the versions package-lock.json pins)"
  if [ -f package-lock.json ]; then npm ci --no-audit --no-fund --loglevel=error; else npm install --no-audit --no-fund --loglevel=error; fi
fi

# the C runtime builds while the TypeScript packages do (tsc is mostly one thread)
log "building the TypeScript packages and the C runtime"
mkdir -p runtime/build
make -s -C runtime > runtime/build/setup.log 2>&1 &
c_build=$!
npm run build --silent
if ! wait "$c_build"; then
  cat runtime/build/setup.log >&2
  log "the C runtime did not build (its output is above, and in runtime/build/setup.log)"
  exit 1
fi

log "done"
