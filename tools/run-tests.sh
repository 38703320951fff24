#!/usr/bin/env bash
# Runs the whole busted suite and ends with one line 'N passed, N failed, N skipped'
# (busted's own summary counts errors apart from failures; both count as failed here).
set -uo pipefail
cd "$(dirname "$0")/.."
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
