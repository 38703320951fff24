#!/usr/bin/env bash
# The mesh export figures of docs/mesh.md (issue 31): for each scene, resolution and field,
# `love . --mesh` timed by /usr/bin/time, then tools/mesh-check.fnl for the topology
# and the farthest vertex from the surface (CPU evaluator, in cells).
#   bash tools/mesh-figures.sh [SCENE...]   (default: organic machined-part)
# Prints one Markdown table row per run. Run nothing else meanwhile: the times are
# wall clock.
set -uo pipefail
cd "$(dirname "$0")/.."
scenes=("$@")
[ ${#scenes[@]} -eq 0 ] && scenes=(organic machined-part)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "| scene | N | field | triangles | mesh s | whole command s | peak memory | topology | farthest vertex |"
echo "|---|---|---|---|---|---|---|---|---|"
for s in "${scenes[@]}"; do
  for n in 128 256; do
    for field in CPU GPU; do
      flag=""; [ "$field" = GPU ] && flag="--gpu"
      f="$out/$s-$n-$field.ply"
      summary=$(/usr/bin/time -f "%e %M" -o "$out/time" env SDL_VIDEODRIVER=offscreen \
                  love . --mesh "scenes/$s.fnl" --out "$f" --resolution "$n" $flag 2>/dev/null)
      read -r wall kb < "$out/time"
      tris=$(echo "$summary" | sed -n 's/.*: \([0-9]*\) triangles.*/\1/p')
      secs=$(echo "$summary" | sed -n 's/.*grid), \([0-9.]*\) s;.*/\1/p')
      check=$(luajit tools/fnl.lua tools/mesh-check.fnl "$f" "scenes/$s.fnl" "$n")
      topo=$([ $? -eq 0 ] && echo "closed, manifold" || echo "NOT MANIFOLD")
      far=$(echo "$check" | sed -n 's/.*largest vertex distance \([0-9.]*\) cells.*/\1/p')
      echo "| $s | $n | $field | $tris | $secs | $wall | $((kb / 1024)) MB | $topo | $far cells |"
    done
  done
done
