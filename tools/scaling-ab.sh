#!/usr/bin/env bash
# The scaling table of issue 29 in ONE interleaved LÖVE run: frame times of the
# benchmark's scaling scene (src/app/bench.fnl's scaling-scene: n spheres in a
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
SDL_VIDEODRIVER=offscreen love "$here/tools/ab-run" "$w" "$h" "${FRAMES:-7}" "${dumps[@]}" \
  | awk -v size="$size" '
    / median / {
      name = $1; sub(/.*\//, "", name); sub(/\.lua$/, "", name)
      split(name, p, "-"); ms[p[1], p[2]] = $3; if (!(p[2] in seen)) { seen[p[2]] = 1; order[++k] = p[2] }
    }
    END {
      first = order[1]
      printf "spheres  %s: base ms (x base %s)   new ms (x new %s)   new/base\n", size, first, first
      for (i = 1; i <= k; i++) {
        n = order[i]
        printf "%7d  %10.1f (%5.2fx)   %10.1f (%5.2fx)   %.2f\n", n, ms["base", n], ms["base", n] / ms["base", first],
               ms["new", n], ms["new", n] / ms["new", first], ms["new", n] / ms["base", n]
      }
    }'
