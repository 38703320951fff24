#!/usr/bin/env bash
# This project's CPU mesher against fogleman/sdf (numpy: batched marching cubes over
# blocks it skips when empty, a thread per core), on the same shapes, region and cell
# size, interleaved (issue 46):
#   bash tools/mesh-vs-fogleman/run.sh [ROUNDS]
# FOGLEMAN_SDF: a checkout of https://github.com/fogleman/sdf (cloned into the work
# folder when unset). What it needs from Python's package index goes into a virtual
# environment there (MESH_VS_FOGLEMAN_DIR, default /tmp/mesh-vs-fogleman). Prints a
# markdown table: median seconds of each side over the rounds, and triangles.
# Not part of the suite: it needs the network once, and its verdict is speed.
set -euo pipefail
cd "$(dirname "$0")/../.."
rounds=${1:-3}
work=${MESH_VS_FOGLEMAN_DIR:-/tmp/mesh-vs-fogleman}
mkdir -p "$work"
sdf=${FOGLEMAN_SDF:-$work/sdf}
if [ ! -d "$sdf/sdf" ]; then
  git clone -q https://github.com/fogleman/sdf "$sdf"
fi
if [ ! -x "$work/venv/bin/python" ]; then
  python3 -m venv "$work/venv"
  "$work/venv/bin/pip" install -q numpy scikit-image scipy meshio Pillow matplotlib
fi
py() { PYTHONPATH="$sdf:tools/mesh-vs-fogleman" "$work/venv/bin/python" tools/mesh-vs-fogleman/bench.py "$@"; }
cases=${MESH_VS_FOGLEMAN_CASES:-"scenes/machined-part.fnl:machined-part scenes/organic.fnl:organic tools/mesh-vs-fogleman/torus.fnl:torus"}
sizes=${MESH_VS_FOGLEMAN_SIZES:-"128 256"}
results=$(mktemp)
trap 'rm -f "$results"' EXIT
for round in $(seq "$rounds"); do
  for c in $cases; do
    scene=${c%%:*} shape=${c##*:}
    for n in $sizes; do
      out=$(luajit tools/fnl.lua tools/mesh-vs-fogleman/ours.fnl "$scene" "$n")
      region=$(echo "$out" | sed -n 's/^region //p')
      read -r ours ours_t < <(echo "$out" | tail -n 1)
      # (Taken whole before the next run starts: read from a process substitution,
      # the line came back while Python was still leaving, on a core the next run
      # wanted.)
      theirs_out=$(py "$shape" $region)
      read -r theirs theirs_t <<< "$theirs_out"
      echo "$shape $n $ours $ours_t $theirs $theirs_t" >> "$results"
      echo "round $round: $shape at $n: ours $ours s ($ours_t triangles), fogleman/sdf $theirs s ($theirs_t)" >&2
    done
  done
done
echo "| shape | cells | this mesher, s | fogleman/sdf, s | ratio | triangles (this / fogleman) |"
echo "|---|---|---|---|---|---|"
for c in $cases; do
  shape=${c##*:}
  for n in $sizes; do
    awk -v s="$shape" -v n="$n" '
      $1 == s && $2 == n { o[++k] = $3; t[k] = $5; ot = $4; tt = $6 }
      function median(a, m,   i, j, x) {
        for (i = 1; i <= m; i++) for (j = i + 1; j <= m; j++) if (a[j] < a[i]) { x = a[i]; a[i] = a[j]; a[j] = x }
        return (m % 2) ? a[(m + 1) / 2] : (a[m / 2] + a[m / 2 + 1]) / 2 }
      END { mo = median(o, k); mt = median(t, k)
            printf "| %s | %d | %.3f | %.3f | %.2f | %d / %d |\n", s, n, mo, mt, mo / mt, ot, tt }' "$results"
  done
done
