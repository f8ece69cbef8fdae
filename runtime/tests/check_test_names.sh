#!/usr/bin/env bash
# The runners' choice of tests by name (`make test-c T=...`, `make test-engines T=...`,
# tests/test_select.h): a name that chooses no test fails before any test runs, saying the near
# names and how to list them; the C function's name (`test_` prefix) chooses the same test.
# Usage: check_test_names.sh RUNNER BIN_DIR ENGINE_TESTS
set -uo pipefail
runner=$1 bin=$2 engines=$3
fails=0
check() { # description, expected exit, output pattern, command...
  local what=$1 want=$2 pattern=$3; shift 3
  local out; out=$("$@" 2>&1); local rc=$?
  if [ "$rc" != "$want" ] || ! grep -qE -- "$pattern" <<<"$out"; then
    echo "FAIL $what (exit $rc, want $want; output: $(head -3 <<<"$out" | tr '\n' '|'))"; fails=$((fails + 1))
  else echo "ok   $what"; fi
}
check "runner: an unknown name fails with its near names" 2 "no test is named 'msc_loop'; near names: msc_request_loop" "$runner" "$bin" msc_loop
check "runner: an unknown name among known ones runs nothing" 2 "^every name: make -C runtime test-c T=--list" "$runner" "$bin" tools_parse nope_nothing
check "runner: the C function's name chooses its test" 0 "^ok   tools_parse .*1 passed, 0 failed" bash -c "\"$runner\" \"$bin\" test_tools_parse | tr '\n' ' '"
check "runner: --list prints every name" 0 "^msc_request_loop$" "$runner" --list
check "engines: an unknown word fails with its near names" 2 "no test is named 'ord_nothing_such'; near names: test_ord" "$engines" ord_nothing_such
check "engines: the test_ prefix is optional" 0 "1 passed, 0 failed" "$engines" report_sup_full_sequence
check "engines: --list prints every name" 0 "^test_report_sup_full_sequence$" "$engines" --list
echo "names: $((7 - fails)) passed, $fails failed"
[ "$fails" = 0 ]
