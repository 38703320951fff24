#!/usr/bin/env bash
# Does the player stay responsive when the scene worker hangs in a function of time?
# Plays an animated scene under Xvfb with a stand-in worker that never answers an
# animate (test/fixtures/worker/fake.fnl hang-animate; RAYMARCHER_SCENE_WORKER), waits
# for the player to pause the clock with its message (the worker is killed after a
# second), presses escape and times how long the player takes to quit.
# Prints 'paused after S s', 'quit S s after escape' and the message (the screen while
# paused: OUT/paused.png). Then a worker that never answers the load: escape while the
# player waits for it ('quit S s after escape during a load'). Exit 0 when all
# happened, 1 when not, 2 when it could not run (a missing tool).
set -uo pipefail
REPO=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$REPO"
for tool in love luajit xvfb-run xdotool; do
  command -v "$tool" >/dev/null || { echo "check-stuck-worker: $tool is not installed" >&2; exit 2; }
done
OUT=${OUT:-$REPO/out/check-stuck-worker}
mkdir -p "$OUT"
cat > "$OUT/spin.fnl" <<'SCENE'
{:objects [{:kind :sphere :pos [0 0 1] :radius (fn [t] (+ 1 (* 0.2 (math.sin t))))}
           {:kind :plane :height 0}]}
SCENE
# A real window (the test suite runs with SDL_VIDEODRIVER=offscreen, which opens none).
unset SDL_VIDEODRIVER
export RAYMARCHER_SCENE_WORKER="luajit $REPO/tools/fnl.lua $REPO/test/fixtures/worker/fake.fnl hang-animate"
xvfb-run -a -s "-screen 0 1280x720x24" bash -c '
  OUT=$1
  # Whatever happens, no player is left running after the check.
  trap "kill \$(jobs -p) 2>/dev/null" EXIT
  # escape PID WINDOW WHEN: press escape in the window, wait up to 10 s for the
  # player to quit, say how long it took; fails when it did not quit or exited
  # other than 0.
  escape() {
    local pid=$1 win=$2 when=$3 pressed rc
    pressed=$(date +%s.%N)
    timeout 10 xdotool windowactivate --sync "$win" key Escape 2>/dev/null || timeout 10 xdotool key Escape
    for i in $(seq 1 200); do
      kill -0 "$pid" 2>/dev/null || break
      sleep 0.05
    done
    if kill -0 "$pid" 2>/dev/null; then echo "still running 10 s after escape$when"; kill -9 "$pid"; return 1; fi
    echo "quit $(echo "$(date +%s.%N) - $pressed" | bc) s after escape$when"
    wait "$pid"; rc=$?
    [ $rc -eq 0 ] || { echo "the player exited $rc after escape$when"; return 1; }
  }
  # No message of an earlier run may be read as one of this run.
  rm -f "$OUT/stdout" "$OUT/stderr" "$OUT/stdout-load" "$OUT/stderr-load"
  love . "$OUT/spin.fnl" >"$OUT/stdout" 2>"$OUT/stderr" &
  pid=$!
  start=$(date +%s.%N)
  paused=""
  for i in $(seq 1 300); do
    if grep -q "the animation is paused" "$OUT/stderr"; then paused=$(date +%s.%N); break; fi
    kill -0 $pid 2>/dev/null || break
    sleep 0.05
  done
  [ -n "$paused" ] && echo "paused after $(echo "$paused - $start" | bc) s"
  win=$(timeout 20 xdotool search --sync --name "Fennel raymarcher" 2>/dev/null | head -1)
  sleep 0.5
  # What a person sees while paused (convert: imagemagick, when installed).
  command -v xwd >/dev/null && command -v convert >/dev/null &&
    xwd -root -silent | convert xwd:- "$OUT/paused.png" 2>/dev/null
  escape "$pid" "$win" "" || exit 1
  grep "the animation is paused" "$OUT/stderr" | head -1
  [ -n "$paused" ] || exit 1
  # A worker that never answers the load: escape while the player waits for it.
  RAYMARCHER_SCENE_WORKER="${RAYMARCHER_SCENE_WORKER% *} hang-load" love . "$OUT/spin.fnl" >"$OUT/stdout-load" 2>"$OUT/stderr-load" &
  pid=$!
  win=$(timeout 20 xdotool search --sync --name "Fennel raymarcher" 2>/dev/null | head -1)
  sleep 1
  escape "$pid" "$win" " during a load" || exit 1
' _ "$OUT"
