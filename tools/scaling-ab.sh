#!/usr/bin/env bash
# The scaling table of issue 29 in ONE interleaved LÖVE run: frame times of the
# benchmark's scaling scene (test/bench/report.fnl's scaling-scene: n spheres in a
# 40 x 40 x 10 region over a floor, hard shadows, one mirror bounce) at 640x360 for
# several counts, drawn by this checkout's code and by another's (BASE, e.g. main's
# worktree), frame after frame in turn, and each count's time over the 10 spheres'
# of the same code. The spheres are made by tools/scaling-dump.fnl, not the scene
# sandbox, so that any count loads.
#   tools/scaling-ab.sh [BASE_DIR] [COUNTS...]     (default: /work/main, 10 1000 10000 100000)
# FRAMES (default 7), SIZE (default 640x360), CELLS (cells per object; default each
# checkout's own), LP_NUM_THREADS (llvmpipe's threads) pass through.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
base=${1:-/work/main}
shift || true
counts=("$@")
[ ${#counts[@]} -gt 0 ] || counts=(10 1000 10000 100000)
size=${SIZE:-640x360}
w=${size%x*}
h=${size#*x}
out=$(mktemp -d /tmp/scaling-ab.XXXXXX)
trap 'rm -rf "$out"' EXIT
dumps=()
for n in "${counts[@]}"; do
  for side in base new; do
    dir=$here; [ "$side" = base ] && dir=$base
    [ -d "$dir" ] || { echo "no checkout at $dir" >&2; exit 2; }
    # (this checkout's tool, run in the other's tree: its modules, its code)
    (cd "$dir" && luajit "$here/tools/fnl.lua" "$here/tools/scaling-dump.fnl" "$n" "$w" "$h" \
       "$out/$side-$n.lua" ${CELLS:-}) >&2
    dumps+=("$out/$side-$n.lua")
  done
done
AB_FRAMES=1 SDL_VIDEODRIVER=offscreen love "$here/tools/ab-run" "$w" "$h" "${FRAMES:-7}" "${dumps[@]}" \
  | awk -v size="$size" '
    # Per dump its frame times, round by round; the ratio of a count is the median
    # over the rounds of its frame over the frame of the first count in the same
    # round (the rounds are drawn in turn, so a busy moment slows both).
    function median(a, n,   i, j, t) {
      for (i = 2; i <= n; i++) { t = a[i]; for (j = i - 1; j >= 1 && a[j] > t; j--) a[j + 1] = a[j]; a[j + 1] = t }
      return n % 2 ? a[(n + 1) / 2] : (a[n / 2] + a[n / 2 + 1]) / 2
    }
    $1 == "frames" {
      name = $2; sub(/.*\//, "", name); sub(/\.lua$/, "", name)
      split(name, p, "-"); side = p[1]; n = p[2]
      if (!(n in seen)) { seen[n] = 1; order[++k] = n }
      rounds = NF - 2
      for (i = 3; i <= NF; i++) t[side, n, i - 2] = $i
    }
    END {
      first = order[1]
      printf "spheres  %s, median ms and median ratio to %d spheres (same code, same round)\n", size, first
      printf "         %-22s %-22s new/base\n", "base", "new"
      for (c = 1; c <= k; c++) {
        n = order[c]
        for (s = 1; s <= 2; s++) {
          side = s == 1 ? "base" : "new"
          for (i = 1; i <= rounds; i++) { a[i] = t[side, n, i]; r[i] = t[side, n, i] / t[side, first, i] }
          ms[side] = median(a, rounds); x[side] = median(r, rounds)
        }
        for (i = 1; i <= rounds; i++) r[i] = t["new", n, i] / t["base", n, i]
        printf "%7d  %8.1f ms (%5.2fx)     %8.1f ms (%5.2fx)     %.2f\n", n, ms["base"], x["base"], ms["new"], x["new"], median(r, rounds)
      }
    }'
