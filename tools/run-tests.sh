#!/usr/bin/env bash
# Runs the whole busted suite and ends with one line 'N passed, N failed, N skipped'
# (busted's own summary counts errors apart from failures; both count as failed here).
# With --check (`make check`): the fast loop, the specs that need no LÖVE window and no
# GPU (codegen_spec's glslangValidator is a plain program), the whole corpus through the
# loader but one file per class through the app, and 2000 fuzz cases.
# The fast tier is every test/*_spec.fnl with the line `;; tier: fast` (a line of its
# own; first in the file by custom): a spec that runs no `love .` window or render and
# no GPU check says so there, and nothing else needs listing.
# No verdict depends on the machine's speed: work is bounded by step and size budgets,
# and a wall-clock limit (a `timeout` around a run) only catches a hang (issue 41).
set -uo pipefail
cd "$(dirname "$0")/.."
if [ "${1:-}" = "--check" ]; then
  shift
  export CORPUS_SAMPLE=1 FUZZ_CASES="${FUZZ_CASES:-2000}"
  mapfile -t fast < <(grep -lx ';; tier: fast' test/*_spec.fnl)
  if [ "${#fast[@]}" -eq 0 ]; then
    echo "run-tests.sh --check: no spec has the line ';; tier: fast'"
    echo "0 passed, 1 failed"
    exit 1
  fi
  set -- "$@" "${fast[@]}"
fi
log=$(mktemp)
trap 'rm -f "$log"' EXIT
busted "$@" 2>&1 | tee "$log"
rc=${PIPESTATUS[0]}
summary=$(grep -E '^[0-9]+ successes? / [0-9]+ failures? / [0-9]+ errors? / [0-9]+ pending' "$log" | tail -n 1)
if [ -z "$summary" ]; then
  echo "busted printed no summary (exit $rc)"
  echo "0 passed, 1 failed"
  exit 1
fi
read -r passed failures errors pending < <(echo "$summary" | awk '{print $1, $4, $7, $10}')
echo "$passed passed, $((failures + errors)) failed, $pending skipped"
exit "$rc"
