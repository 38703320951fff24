#!/usr/bin/env bash
# Runs the whole busted suite and ends with one line 'N passed, N failed, N skipped'
# (busted's own summary counts errors apart from failures; both count as failed here).
# With --check (`make check`): the fast loop, the specs that need no LÖVE window and no
# GPU (codegen_spec's glslangValidator is a plain program), the whole corpus through the
# loader but one file per class through the app, 500 fuzz cases, and no test tagged
# #timing (those print a time and judge nothing). Its spec files run as separate busted
# processes, one per core at a time (CHECK_JOBS=n for another number), the longest first
# by the last run's times (test/out/check-seconds.txt); each file's output is printed
# whole, in that order.
# The fast tier is every test/*_spec.fnl with the line `;; tier: fast` (a line of its
# own; first in the file by custom): a spec that runs no `love .` window or render and
# no GPU check says so there, and nothing else needs listing.
# No verdict depends on the machine's speed: work is bounded by step and size budgets,
# and a wall-clock limit (a `timeout` around a run) only catches a hang (issue 41).
set -uo pipefail
cd "$(dirname "$0")/.."

summary_of() {
  # busted's last summary line in file $1, as "passed failures errors pending".
  grep -E '^[0-9]+ success(es)? / [0-9]+ failures? / [0-9]+ errors? / [0-9]+ pending' "$1" |
    tail -n 1 | awk '{print $1, $4, $7, $10}'
}

if [ "${1:-}" = "--check" ]; then
  shift
  export CORPUS_SAMPLE=1 FUZZ_CASES="${FUZZ_CASES:-500}"
  mapfile -t fast < <(grep -lx ';; tier: fast' test/*_spec.fnl)
  if [ "${#fast[@]}" -eq 0 ]; then
    echo "run-tests.sh --check: no spec has the line ';; tier: fast'"
    echo "0 passed, 1 failed"
    exit 1
  fi
  mkdir -p test/out
  times=test/out/check-seconds.txt
  # The longest first (a file not timed yet counts as longest), so that the last to
  # start are short and the cores finish together.
  mapfile -t order < <(for f in "${fast[@]}"; do
                         t=$(awk -v f="$f" '$2 == f {print $1}' "$times" 2>/dev/null)
                         echo "${t:-1e9} $f"
                       done | sort -g -r | awk '{print $2}')
  logs=$(mktemp -d)
  trap 'rm -rf "$logs"' EXIT
  run_one() {
    # One spec file: its output in $logs/NAME.log, its exit code and seconds in .rc.
    local f=$1 name start
    shift
    name=$(basename "$f")
    start=$(date +%s.%N)
    # Tests tagged #timing print how long something takes and judge nothing: the
    # full suite runs them, the fast loop does not.
    busted --exclude-tags=timing "$@" "$f" > "$logs/$name.log" 2>&1
    echo "$? $(awk -v s="$start" -v e="$(date +%s.%N)" 'BEGIN {printf "%.1f", e - s}')" \
      > "$logs/$name.rc"
    # Progress while the others run; the file's whole output comes at the end.
    echo "check: $f done in $(awk '{print $2}' "$logs/$name.rc") s: $(summary_of "$logs/$name.log" |
      awk '{print $1 " passed, " $2 + $3 " failed, " $4 " skipped"}')" >&2
  }
  export -f summary_of
  export -f run_one
  export logs
  printf '%s\n' "${order[@]}" |
    xargs -P "${CHECK_JOBS:-$(nproc)}" -I{} bash -c 'run_one "$@"' _ {} "$@"
  read -r passed failures errors pending <<< "0 0 0 0"
  rc=0
  : > "$times.new"
  for f in "${order[@]}"; do
    name=$(basename "$f")
    cat "$logs/$name.log"
    read -r code seconds < "$logs/$name.rc"
    echo "$seconds $f" >> "$times.new"
    s=$(summary_of "$logs/$name.log")
    if [ -z "$s" ]; then
      echo "$f: busted printed no summary (exit $code)"
      failures=$((failures + 1))
      rc=1
      continue
    fi
    read -r p fl er pe <<< "$s"
    passed=$((passed + p)) failures=$((failures + fl)) errors=$((errors + er))
    pending=$((pending + pe))
    [ "$code" -ne 0 ] && rc=1
  done
  mv "$times.new" "$times"
  echo "$passed passed, $((failures + errors)) failed, $pending skipped"
  exit "$rc"
fi

log=$(mktemp)
trap 'rm -f "$log"' EXIT
busted "$@" 2>&1 | tee "$log"
rc=${PIPESTATUS[0]}
summary=$(summary_of "$log")
if [ -z "$summary" ]; then
  echo "busted printed no summary (exit $rc)"
  echo "0 passed, 1 failed"
  exit 1
fi
read -r passed failures errors pending <<< "$summary"
echo "$passed passed, $((failures + errors)) failed, $pending skipped"
exit "$rc"
