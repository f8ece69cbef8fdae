#!/usr/bin/env bash
# Runs the TypeScript builds, the CLI smoke test, a simulation told by `contract trace`, a real run
# told by it, `contract serve`, and the language and codegen tests
# on other Node versions than the one that builds the project (README.md "Requirements": Node 20,
# 22, 24 and 26 are supported).
#   bash scripts/test-node-versions.sh            # Node 22, 24 and 26
#   NODE_VERSIONS="24" bash scripts/test-node-versions.sh
# Each Node is installed once from the npm registry (the `node-linux-<arch>` package, a plain
# binary; nothing is added to package.json) into $NODE_VERSIONS_DIR (default
# ~/.cache/contract-studio/node). Needs a set-up checkout (scripts/setup.sh: dist/ built).
# Not part of `make test` (several minutes): `make test-node-versions`.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
VERSIONS="${NODE_VERSIONS:-22 24 26}"
CACHE="${NODE_VERSIONS_DIR:-$HOME/.cache/contract-studio/node}"
case "$(uname -m)" in
    x86_64) ARCH=x64 ;;
    aarch64 | arm64) ARCH=arm64 ;;
    *) echo "test-node-versions: no node-linux package for $(uname -m)" >&2; exit 2 ;;
esac
CLI="$ROOT/packages/cli/bin/contract.js"
for dist in language codegen cli; do
    if [ ! -d "$ROOT/packages/$dist/dist" ]; then
        echo "test-node-versions: packages/$dist/dist is missing: run scripts/setup.sh (or npm run build) first" >&2
        exit 2
    fi
done

SCRATCH="$(mktemp -d "${TMPDIR:-/tmp}/contract-node-versions-XXXXXX")"
trap 'rm -rf "$SCRATCH"' EXIT
FAILED=()
SUMMARY=()

now() { date +%s.%N; }
elapsed() { awk -v a="$1" -v b="$(now)" 'BEGIN { printf "%.1f", b - a }'; }

# step NAME COMMAND...: runs a step, records its time and result.
step() {
    local name="$1"; shift
    local start; start="$(now)"
    echo "== $name"
    if "$@"; then
        SUMMARY+=("ok    $(elapsed "$start") s  $name")
    else
        SUMMARY+=("FAIL  $(elapsed "$start") s  $name")
        FAILED+=("$name")
    fi
}

install_node() {
    local v="$1" dir="$CACHE/node$1"
    local bin="$dir/node_modules/node-linux-$ARCH/bin/node"
    if [ ! -x "$bin" ]; then
        mkdir -p "$dir"
        npm install --no-save --no-audit --no-fund --loglevel=error --prefix "$dir" "node-linux-$ARCH@$v" >&2
    fi
    echo "$bin"
}

# The CLI on both examples: check (0 errors), then generate into copies outside the repository:
# regenerating the committed src-gen writes nothing, and a fresh generate gives the same bytes
# (docs/ci.md: src-gen is committed and must not depend on the machine).
cli_smoke() {
    local node="$1" work="$SCRATCH/$2"
    for example in tutorial mobile-robot; do
        "$node" "$CLI" check "$ROOT/examples/$example" 2>&1 | tail -n 1 | tee "$work.check"
        grep -q '^0 errors' "$work.check" || return 1
        rm -rf "$work/$example" "$work/fresh-$example"
        mkdir -p "$work/fresh-$example"
        cp -r "$ROOT/examples/$example" "$work/$example"
        "$node" "$CLI" generate "$work/$example" 2>&1 | tail -n 1 | tee "$work.gen"
        grep -q ': 0 created, 0 updated, [0-9]* kept, 0 orphaned, 0 error(s)' "$work.gen" || return 1
        cp "$ROOT/examples/$example"/*.contract "$work/fresh-$example/"
        "$node" "$CLI" generate "$work/fresh-$example" > /dev/null 2>&1 || return 1
        # user code lives in the committed tree only: compare the Makefiles, which hold none
        (cd "$work/fresh-$example/src-gen" && find . -name Makefile -o -name 'makecontrol*') | sort | while read -r f; do
            cmp "$work/fresh-$example/src-gen/$f" "$ROOT/examples/$example/src-gen/$f" || exit 1
        done || return 1
    done
}

# The tutorial's scenarios simulated with --trace (virtual time: the same bytes on every Node),
# then told by `contract trace`: trace file and story must equal those of the Node that built the
# project (the simulator's native harness is built once, in the scratch cache, by the first call).
sim_trace() {
    local node="$1" out="$SCRATCH/sim-$2"
    mkdir -p "$out"
    "$node" "$CLI" simulate "$ROOT/examples/tutorial" "$ROOT"/examples/tutorial/scenarios/*.scenario \
        --trace "$out/trace.jsonl" --cache-dir "$SCRATCH/cache" > /dev/null || return 1
    "$node" "$CLI" trace "$out/trace.jsonl" > "$out/story.txt" || return 1
    cmp "$out/trace.jsonl" "$SCRATCH/sim-reference/trace.jsonl" && cmp "$out/story.txt" "$SCRATCH/sim-reference/story.txt"
}

# A real run of the tutorial (bwrap: 4 s, the build service in-process, gcc, the runtime) and its
# story: the run must end cleanly and `contract trace` tell SUP's rule changes with their causes.
run_trace() {
    local node="$1" work="$SCRATCH/run-$2"
    if ! command -v bwrap > /dev/null; then echo "no bwrap: run step skipped"; return 0; fi
    rm -rf "$work" && mkdir -p "$work" && cp -r "$ROOT/examples/tutorial" "$work/tutorial" && rm -rf "$work/tutorial/logs"
    "$node" "$CLI" run "$work/tutorial" --duration 4s --sandbox bwrap > "$work/run.out" 2>&1 || { tail -n 20 "$work/run.out"; return 1; }
    "$node" "$CLI" trace "$work/tutorial/logs" > "$work/story.txt" || return 1
    grep -q 'SUP  rule action.SECOND active   <- MAA:2 = "disconnected"' "$work/story.txt" || { grep ' rule ' "$work/story.txt"; return 1; }
}

# `contract serve` (the IDE and the build service): the page, opened with the printed URL's
# token, and the jobs API with the token's cookie.
serve_smoke() {
    local node="$1" work="$SCRATCH/serve-$2"
    rm -rf "$work" && mkdir -p "$work" && cp -r "$ROOT/examples/tutorial" "$work/tutorial"
    "$node" "$CLI" serve "$work/tutorial" --port 0 > "$work/serve.log" 2>&1 &
    local pid=$! url="" ok=1
    for _ in $(seq 1 100); do
        url="$(grep -o 'http://[^ ]*' "$work/serve.log" | head -n 1 || true)"
        [ -n "$url" ] && break
        sleep 0.1
    done
    if [ -n "$url" ] && curl -sf -L -c "$work/cookies" -b "$work/cookies" "$url" | grep -q '<title>ContrACT Studio'; then
        curl -sf -b "$work/cookies" "${url%%/\?*}/api/jobs" > /dev/null && ok=0
    fi
    kill "$pid" 2> /dev/null; wait "$pid" 2> /dev/null || true
    [ "$ok" -eq 0 ] || { cat "$work/serve.log"; return 1; }
}

# The TypeScript builds (scripts/setup.sh's `npm run build`) under that Node: Langium's CLI does
# not run on Node 24.20+, so the build regenerates the parser only when the grammar changed
# (packages/language/scripts/generate-parser.mjs); this step fails if it ever needs it again.
build_all() {
    local node="$1"
    (cd "$ROOT" && PATH="$(dirname "$node"):$PATH" npm run build --silent)
}

vitest_in() {
    local node="$1" pkg="$2"
    (cd "$ROOT/packages/$pkg" && "$node" "$ROOT/node_modules/vitest/vitest.mjs" run --reporter=dot)
}

TOTAL_START="$(now)"
step "node $(node --version): simulation reference (tutorial scenarios, contract trace)" sim_trace node reference
for v in $VERSIONS; do
    start="$(now)"
    NODE_BIN="$(install_node "$v")"
    SUMMARY+=("ok    $(elapsed "$start") s  node $v: install (cached after the first time)")
    echo "== node $v: $("$NODE_BIN" --version) ($NODE_BIN)"
    step "node $v: the TypeScript builds (npm run build)" build_all "$NODE_BIN"
    step "node $v: CLI check + generate (tutorial, mobile-robot)" cli_smoke "$NODE_BIN" "node$v"
    step "node $v: simulation told by contract trace (same bytes as the reference)" sim_trace "$NODE_BIN" "node$v"
    step "node $v: contract run (bwrap, tutorial 4 s) told by contract trace" run_trace "$NODE_BIN" "node$v"
    step "node $v: contract serve (the IDE page, the jobs API)" serve_smoke "$NODE_BIN" "node$v"
    step "node $v: language tests" vitest_in "$NODE_BIN" language
    step "node $v: codegen tests" vitest_in "$NODE_BIN" codegen
done

echo
printf '%s\n' "${SUMMARY[@]}"
echo "total $(elapsed "$TOTAL_START") s"
if [ "${#FAILED[@]}" -gt 0 ]; then
    echo "test-node-versions: ${#FAILED[@]} step(s) failed" >&2
    exit 1
fi
