#!/usr/bin/env bash
# Does the player ever show a picture that mixes two scene states? Plays
# test/states/hue.fnl (every surface's hue is the :hue parameter) under Xvfb with
# the HUD hidden, and grabs the window (xwd, ~15 ms a grab) every GRAB_S seconds
# through four scenarios:
#   drag        the F2 panel's :hue slider dragged from 0.1 to 0.9 in 3 s
#   value-edit  the file's :hue literal edited to 0.6 (a value edit: uniforms only)
#   structural  the file rewritten with one more object and :hue 0.3 (a new shader)
#   animated    hue.fnl with its :hue a function of time: 24 to 216 degrees and back
#               every 8 s (0.1 to 0.9 of :hue), 48 degrees a second; two moments
#               0.125 s apart differ by 6 degrees, the classifier's tolerance
# tools/check-states.fnl then cuts every frame (left of the panel, above the message
# area) into horizontal strips, reads each strip's state from its hue, and counts the
# frames whose strips disagree (src/verify/states.fnl); the worst frame of each
# scenario is saved as OUT/NAME-worst.png.
#
#   tools/check-states.sh [PLAYER_DIR]     # default: this checkout
#   tools/check-states.sh --calibrate      # strip spread of single-state renders
#
# PLAYER_DIR is the LÖVE game folder to run (another checkout or worktree); the scenes
# and the classifier always come from this checkout. Environment: OUT (default
# out/check-states), GRAB_S (0.15), KEEP=1 keeps the window dumps (3.7 MB each),
# SCENES (test/states: the folder holding hue.fnl;
# test/states/light has versions light enough for every frame to be drawn whole).
# The scene played is test/states/hue-colours.fnl (the :hue parameter, its colours,
# the view: the same for every folder) followed by SCENES/hue.fnl (the objects), one
# file: a scene file cannot load another.
# Exit 0: no frame mixes states; 1: some frame does; 2: the check could not run
# (no window, a scenario whose state never changed, a missing tool).
set -euo pipefail

die() { echo "check-states: $*" >&2; exit 2; }

REPO=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
OUT=${OUT:-$REPO/out/check-states}
GRAB_S=${GRAB_S:-0.15}
SCENES_ARG=${SCENES:-$REPO/test/states}
SCENES=$(cd "$SCENES_ARG" 2>/dev/null && pwd) || die "no scene folder $SCENES_ARG"
[ -f "$SCENES/hue.fnl" ] || die "$SCENES has no hue.fnl"
HEAD_FILE=$REPO/test/states/hue-colours.fnl
[ -f "$HEAD_FILE" ] || die "no $HEAD_FILE"
# The scene's text: the shared head, then the folder's objects.
scene_text() { cat "$HEAD_FILE" "$SCENES/hue.fnl"; }
TITLE="Fennel raymarcher"

for tool in love luajit xvfb-run xdotool xwd bc; do
  command -v "$tool" >/dev/null || die "$tool is not installed (make check-states installs it: xvfb, xdotool, x11-apps, bc)"
done

if [ "${1:-}" = "--calibrate" ]; then
  # Single-state pictures: whole renders at several :hue values, and the same scaled
  # down to 1/8 and up again with linear filtering (what a coarse picture looks like).
  command -v convert >/dev/null || die "convert (ImageMagick) is needed for --calibrate"
  dir="$OUT/calibrate"; rm -rf "$dir"; mkdir -p "$dir"
  for v in 0.0 0.1 0.3 0.6 0.9 1.0; do
    scene_text | sed "s/(param :hue 0\.1 /(param :hue $v /" > "$dir/hue-$v.fnl"
    (cd "$REPO" && SDL_VIDEODRIVER=offscreen love . --render "$dir/hue-$v.fnl" \
       --out "$dir/hue-$v.png" --size 1280x720 --samples 1 >/dev/null) || die "render of :hue $v failed"
    convert "$dir/hue-$v.png" -filter Triangle -resize 160x90 -resize 1280x720\! "$dir/hue-$v-coarse.png"
  done
  cd "$REPO" && exec luajit tools/fnl.lua tools/check-states.fnl --calibrate "$dir"/hue-*.png
fi

PLAYER=$(cd "${1:-$REPO}" 2>/dev/null && pwd) || die "no player directory ${1:-}"
[ -f "$PLAYER/main.fnl" ] && [ -f "$PLAYER/conf.lua" ] || die "$PLAYER is not the player's folder (no main.fnl and conf.lua)"

# Everything below runs inside its own X server, in a real window (make test sets
# SDL_VIDEODRIVER=offscreen, which would open none).
unset SDL_VIDEODRIVER
if [ -z "${CHECK_STATES_DISPLAY:-}" ]; then
  exec xvfb-run -a -s "-screen 0 1280x720x24" \
       env CHECK_STATES_DISPLAY=1 OUT="$OUT" GRAB_S="$GRAB_S" SCENES="$SCENES" bash "$0" "$PLAYER"
fi

WORK="$OUT/frames"
# Only what this script writes is removed: OUT may be a folder with other things in it.
rm -rf "$WORK"; rm -f "$OUT"/*-worst.png; mkdir -p "$WORK"
scene_text > "$WORK/hue.fnl"
# The animated scene: a triangle wave of time in place of the :hue parameter.
scene_text \
  | sed 's/^(local hue (param :hue .*$/(local hue (fn [t] (let [p (% (\/ t 8) 1)] (+ 0.1 (* 0.8 (if (< p 0.5) (* 2 p) (- 2 (* 2 p))))))))/' \
  > "$WORK/hue-animated.fnl"
grep -q '^(local hue (fn' "$WORK/hue-animated.fnl" || die "$HEAD_FILE has no (local hue (param :hue ...)) line"
. "$REPO/tools/window-stop.sh"
T0=$(date +%s.%N)
say() { printf '[%5.1f s] %s\n' "$(echo "$(date +%s.%N) - $T0" | bc)" "$*"; }

start_player() { # SCENE LOG
  love "$PLAYER" "$1" > "$2" 2>&1 &
  LOVE_PID=$!
  WID=""
  for _ in $(seq 1 300); do
    WID=$(xdotool search --name "^$TITLE" 2>/dev/null | head -1 || true)
    [ -n "$WID" ] && break
    kill -0 "$LOVE_PID" 2>/dev/null || die "the player exited: $(tail -5 "$2")"
    sleep 0.2
  done
  [ -n "$WID" ] || die "no player window after 60 s: $(tail -5 "$2")"
}

stop_player() {
  kill "$LOVE_PID" 2>/dev/null || true
  wait "$LOVE_PID" 2>/dev/null || true
  LOVE_PID=""
}

# Wait until two grabs a second apart are the same picture and every strip of it
# shows a state (the image is drawn and no longer changing), at most LIMIT seconds;
# go on either way.
drawn() { # XWD
  (cd "$REPO" && luajit tools/fnl.lua tools/check-states.fnl --calibrate "$1") \
    | grep -q "every strip has a state"
}
wait_still() { # LIMIT
  local a="$WORK/still-a.xwd" b="$WORK/still-b.xwd" t=0
  xwd -id "$WID" -silent -out "$a"
  while [ "$t" -lt "$1" ]; do
    sleep 1; t=$((t + 1))
    xwd -id "$WID" -silent -out "$b"
    if cmp -s "$a" "$b" && drawn "$b"; then
      rm -f "$a" "$b"; say "picture still after ${t} s"; return 0
    fi
    mv "$b" "$a"
  done
  rm -f "$a" "$b"
  say "picture still changing after $1 s; going on"
}

grab_start() { # NAME
  mkdir -p "$WORK/$1"
  ( i=0
    while :; do
      i=$((i + 1))
      xwd -id "$WID" -silent -out "$(printf '%s/%s/%04d.xwd' "$WORK" "$1" "$i")" 2>/dev/null || exit 0
      sleep "$GRAB_S"
    done ) &
  GRAB_PID=$!
}

grab_stop() {
  kill "$GRAB_PID" 2>/dev/null || true
  wait "$GRAB_PID" 2>/dev/null || true
  GRAB_PID=""
}

# A file edit as an editor saves it: written beside it, then renamed over it.
write_scene() { # FILE (text on stdin)
  cat > "$1.tmp"; mv "$1.tmp" "$1"
}

# The panel's first row is the :hue slider (src/app/panel.fnl: a 300 px panel 8 px
# from the right edge, sliders from 8 + 112 px into it, 172 px wide, rows from y 32,
# 22 high).
SLIDER_X0=$((1280 - 300 - 8 + 8 + 112))
SLIDER_W=172
SLIDER_Y=$((32 + 11))
slider_x() { echo "$SLIDER_X0 + $1 * ($SLIDER_W - 1)" | bc | cut -d. -f1; }

say "player: $PLAYER, scenes: $SCENES"
start_player "$WORK/hue.fnl" "$WORK/player.log"
say "window $WID"
# Hide the HUD first: its fps figures change every frame, so the picture would never
# be still (the key waits in the event queue until the scene has loaded).
xdotool key --window "$WID" h
wait_still 90
xdotool key --window "$WID" F2    # open the parameter panel
wait_still 30

say "drag: the :hue slider from 0.1 to 0.9 over 3 s"
grab_start drag
sleep 0.5
xdotool mousemove --window "$WID" "$(slider_x 0.1)" "$SLIDER_Y" mousedown 1
for i in $(seq 1 20); do
  sleep 0.15
  xdotool mousemove --window "$WID" "$(slider_x "$(echo "0.1 + 0.8 * $i / 20" | bc -l)")" "$SLIDER_Y"
done
xdotool mouseup 1
sleep 5
grab_stop
wait_still 30

say "value-edit: the file's :hue 0.1 -> 0.6"
grab_start value-edit
sleep 1
scene_text | sed "s/(param :hue 0\.1 /(param :hue 0.6 /" | write_scene "$WORK/hue.fnl"
sleep 6
grab_stop
wait_still 30

say "structural: one more object and :hue 0.3"
grab_start structural
sleep 1
# The cone goes first in the :objects vector (a scene may end that vector with a
# call whose values it spreads, test/states/field's members).
scene_text | sed -e "s/(param :hue 0\.1 /(param :hue 0.3 /" \
  | perl -0pe 's/:objects(\s*)\[/:objects$1\[{:kind :capped-cone :height 2 :radius1 0.9 :radius2 0.3 :pos [3.5 -4 1] :color c :mirror 0}\n  /' \
  | write_scene "$WORK/hue.fnl"
grep -q capped-cone "$WORK/hue.fnl" || die "the structural edit did not apply to $SCENES/hue.fnl"
sleep 10
grab_stop
# Left alone, the picture gets its anti-aliased still (bands of the same state, which
# the frames above may hold too): the player says when it is whole (at most 120 s).
t=0
until grep -q "^anti-aliased still: " "$WORK/player.log" || [ "$t" -ge 120 ]; do
  sleep 1; t=$((t + 1))
done
if grep -q "^anti-aliased still: " "$WORK/player.log"; then
  say "$(grep "^anti-aliased still: " "$WORK/player.log" | tail -1)"
else
  say "no anti-aliased still 120 s after the structural edit"
fi
stop_player

say "animated: hue.fnl with its hue a function of time, 48 degrees a second"
start_player "$WORK/hue-animated.fnl" "$WORK/player-animated.log"
sleep 5
xdotool key --window "$WID" h
sleep 1
grab_start animated
sleep 8
grab_stop
stop_player
say "grabbed; classifying"

status=0
(cd "$REPO" && luajit tools/fnl.lua tools/check-states.fnl --out "$OUT" --two-states value-edit,structural \
   drag="$WORK/drag" value-edit="$WORK/value-edit" structural="$WORK/structural" \
   animated="$WORK/animated") || status=$?
say "done"
[ "${KEEP:-}" = 1 ] || find "$WORK" -name '*.xwd' -delete
exit "$status"
