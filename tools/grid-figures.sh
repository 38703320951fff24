#!/usr/bin/env bash
# Issue 29's grid and blend scaling in ONE interleaved LÖVE run: frame times at
# 640x360 of tools/grid-scene.fnl's mixed (boxes, tori, capsules) and blend (a smooth
# union of spheres) scenes for several counts, by this checkout's code, and by
# BASE's (another checkout) for the counts it can draw (it may refuse the larger).
#   tools/grid-figures.sh [BASE_DIR] [COUNTS...]    (default: none, 10 100 1000 10000)
# FRAMES (default 5) and SIZE (default 640x360) pass through.
set -uo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
base=${1:-}
shift || true
counts=("$@")
[ ${#counts[@]} -gt 0 ] || counts=(10 100 1000 10000)
size=${SIZE:-640x360}
w=${size%x*}
h=${size#*x}
out=$(mktemp -d /tmp/grid-figures.XXXXXX)
trap 'rm -rf "$out"' EXIT
dumps=()
for kind in mixed blend; do
  for n in "${counts[@]}"; do
    luajit "$here/tools/fnl.lua" "$here/tools/grid-scene.fnl" "$kind" "$n" "$out/$kind-$n.fnl" || exit 1
    for side in base new; do
      dir=$here
      if [ "$side" = base ]; then [ -n "$base" ] || continue; dir=$base; fi
      if (cd "$dir" && luajit "$here/tools/fnl.lua" "$here/tools/ab-dump.fnl" "$out/$kind-$n.fnl" "$w" "$h" \
            "$out/$side-$kind-$n.lua") 2> "$out/err"; then
        dumps+=("$out/$side-$kind-$n.lua")
      else
        echo "$side $kind $n: $(grep -m1 -o 'fnl:[^ ]*: .*' "$out/err" | cut -c1-160)" >&2
      fi
    done
  done
done
SDL_VIDEODRIVER=offscreen love "$here/tools/ab-run" "$w" "$h" "${FRAMES:-5}" "${dumps[@]}" | sed "s|$out/||"
