#!/usr/bin/env bash
# The player's own figures, as a person sees them: for each scene, in a real 1280x720
# window under Xvfb, how long after its shader was ready the first whole picture
# reached the screen, and the median frame time while the camera turns (the `a` key
# held for HOLD_S seconds) against the target rate. Prints one line a scene.
#
#   tools/player-rates.sh [SCENE ...]     # default: every scenes/*.fnl
#
# Environment: HOLD_S (5), TARGET_FPS (30), PLAYER (the game folder to run: this
# checkout). Needs xvfb-run and xdotool
# (`make check-states` installs them).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
HOLD_S=${HOLD_S:-5}
TARGET_FPS=${TARGET_FPS:-30}
for tool in love xvfb-run xdotool; do
  command -v "$tool" >/dev/null || { echo "player-rates: $tool is not installed" >&2; exit 2; }
done
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(scenes/*.fnl)
log=$(mktemp)
trap 'rm -f "$log"' EXIT

one() {
  local scene=$1
  stdbuf -oL love "${PLAYER:-.}" "$scene" --target-fps "$TARGET_FPS" >"$log" 2>&1 &
  local pid=$!
  local wid="" i
  for i in $(seq 1 600); do
    grep -q "^first picture" "$log" && wid=$(xdotool search --name "Fennel raymarcher" 2>/dev/null | head -1)
    [ -n "$wid" ] && break
    sleep 0.1
  done
  if [ -z "$wid" ]; then echo "$scene: no first picture in 60 s"; kill "$pid"; return; fi
  sleep 1
  xdotool keydown --window "$wid" a
  sleep "$HOLD_S"
  xdotool keyup --window "$wid" a
  for i in $(seq 1 1200); do grep -q "^changing:" "$log" && break; sleep 0.1; done
  kill "$pid" 2>/dev/null || true
  wait "$pid" 2>/dev/null || true
  local first moving
  first=$(grep -m1 "^first picture" "$log" | sed -E 's/.* ([0-9]+ ms) after.*\((.*)\)/\1 (\2)/')
  moving=$(grep -m1 "^changing:" "$log" | sed -E 's/^changing: //')
  printf '%-28s first picture %-18s turning: %s\n' "$scene" "$first" "${moving:-no figure}"
}

# Under Xvfb this script runs itself again with --one SCENE.
if [ "${1:-}" = --one ]; then one "$2"; exit 0; fi
for s in "${scenes[@]}"; do
  xvfb-run -a -s "-screen 0 1280x720x24" bash "$0" --one "$s" 2>/dev/null | grep -v "^ALSA\|^AL lib" || true
done
