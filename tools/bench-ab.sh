#!/usr/bin/env bash
# Interleaved A/B frame times: `love . --bench` of each scene in another checkout
# (BASE, e.g. `git archive BASE_COMMIT | tar -x -C /tmp/base`) and in this one, in
# turn, ROUNDS times (default 3), so that a noisy shared machine slows both alike.
#   tools/bench-ab.sh /tmp/base test/bench/tori-capsules.fnl scenes/organic.fnl
# Prints "round side scene ms" lines; compare the medians of each side.
set -uo pipefail
base=${1:?usage: tools/bench-ab.sh BASE_DIR SCENE...}
shift
here=$(cd "$(dirname "$0")/.." && pwd)
export SDL_VIDEODRIVER=offscreen
for round in $(seq 1 "${ROUNDS:-3}"); do
  for side in base new; do
    dir=$here; [ "$side" = base ] && dir=$base
    for scene in "$@"; do
      ms=$(cd "$dir" && timeout 300 love . --bench "$scene" --size "${SIZE:-640x360}" --frames "${FRAMES:-7}" 2>&1 \
           | sed -n 's/.*median \([0-9.]*\) ms.*/\1/p')
      echo "$round $side $scene ${ms:-failed}"
    done
  done
done
