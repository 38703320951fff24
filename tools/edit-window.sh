#!/usr/bin/env bash
# The time from saving a scene file to its new picture on screen, in a real window
# (Xvfb, 1280x720), for each showcase scene and four edits made when the player is
# idle (its still drawn, its helper done), each typed into the file's :objects vector
# as a person would (tools/edit-window.fnl --edit):
#   added     a magenta sphere 4 units in front of the camera (a structural edit)
#   kind      that sphere made a box (structural)
#   operation that box twisted (structural)
#   value     that box made green (the same shader, new uniforms)
# Each is saved as an editor saves (written beside the file, renamed over it), and
# read by the player's own file watcher. The player writes a line a frame
# (RAYMARCH_FRAME_LOG: the time, what drew it, the scene it shows) and the window is
# grabbed (xwd) every GRAB_S seconds meanwhile; tools/edit-window.fnl reads both and
# prints a line an edit:
#   first       ms from the save to the end of the first frame showing the new scene,
#               and what drew it (preview: the CPU reference's picture while the
#               shader is compiled; interpreter; shader)
#   own         ms to the first frame drawn by the new scene's own shader
#   longest     the longest time between two frames from the save until then (ms)
#   back        frames after the first new one that show the old scene (0)
#   screen      the first grab that differs from the picture before the save: the
#               ms at which that grab started and ended
#   sback       grabs after that one that show the old picture again (0)
# Exit 0 when every edit showed and none went back; 1 otherwise; 2 when it could not
# run. Usage: tools/edit-window.sh [SCENE...]   (default: the showcase scenes)
# Environment: PLAYER (the game folder, default this checkout), OUT (out/edit-window),
# GRAB_S (0.03), KEEP=1 keeps the grabs (3.7 MB each), PLAYER_ARGS (e.g.
# --interpret-edits).
set -euo pipefail

die() { echo "edit-window: $*" >&2; exit 2; }

REPO=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
OUT=${OUT:-$REPO/out/edit-window}
GRAB_S=${GRAB_S:-0.03}
PLAYER=$(cd "${PLAYER:-$REPO}" 2>/dev/null && pwd) || die "no player directory $PLAYER"
TITLE="Fennel raymarcher"
SCENES=${*:-$(for n in gallery lighting twisted-tower machined-part organic platonic-shelf flower colonnade; do printf '%s ' "$REPO/scenes/$n.fnl"; done)}

for tool in love luajit xvfb-run xdotool xwd; do
  command -v "$tool" >/dev/null || die "$tool is not installed (tools/install-deps.sh xvfb xdotool x11-apps)"
done

unset SDL_VIDEODRIVER
if [ -z "${EDIT_WINDOW_DISPLAY:-}" ]; then
  exec xvfb-run -a -s "-screen 0 1280x720x24" \
       env EDIT_WINDOW_DISPLAY=1 OUT="$OUT" GRAB_S="$GRAB_S" PLAYER="$PLAYER" bash "$0" $SCENES
fi

mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd)
. "$REPO/tools/window-stop.sh"

# A file edit as an editor saves it: written beside it, then renamed over it.
write_scene() { cat > "$1.tmp"; mv "$1.tmp" "$1"; }

# Until two grabs a second apart are the same picture (at most 90 s), then 3 s more
# for the helper's background shaders (the folded one changes no pixel).
wait_still() { # DIR
  local a="$1/still-a.xwd" b="$1/still-b.xwd" t=0
  xwd -id "$WID" -silent -out "$a"
  while [ "$t" -lt 90 ]; do
    sleep 1; t=$((t + 1))
    xwd -id "$WID" -silent -out "$b"
    cmp -s "$a" "$b" && break
    mv "$b" "$a"
  done
  rm -f "$a" "$b"
  sleep 3
}

grab() { # DIR SECONDS
  ( i=0; end=$(echo "$EPOCHREALTIME + $2" | bc)
    while [ "$(echo "$EPOCHREALTIME < $end" | bc)" = 1 ]; do
      i=$((i + 1)); t0=$EPOCHREALTIME
      xwd -id "$WID" -silent -out "$(printf '%s/%04d.xwd' "$1" "$i")" 2>/dev/null || exit 0
      echo "$i $t0 $EPOCHREALTIME" >> "$1/grabs"
      sleep "$GRAB_S"
    done ) &
  GRAB_PID=$!
}

status=0
printf '%-16s %-15s %9s %-12s %9s %9s %6s %15s %6s\n' scene edit first "drawn by" own longest back screen sback
for s in $SCENES; do
  name=$(basename "$s" .fnl)
  dir="$OUT/$name"
  rm -rf "$dir"; mkdir -p "$dir"
  [ -f "$s" ] || die "no scene $s"
  cp "$s" "$dir/original.fnl"
  cp "$s" "$dir/scene.fnl"
  # An empty shader cache for each scene: an edit's shader is a new one, as for a
  # person editing (a cache hit skips the helper and its preview).
  rm -rf "$dir/mesa"
  (cd "$PLAYER" && MESA_SHADER_CACHE_DIR="$dir/mesa" RAYMARCH_FRAME_LOG="$dir/frames.log" \
     exec love . "$dir/scene.fnl" ${PLAYER_ARGS:-}) \
    > "$dir/player.log" 2>&1 &
  LOVE_PID=$!
  WID=""
  for _ in $(seq 1 300); do
    WID=$(xdotool search --name "^$TITLE" 2>/dev/null | head -1 || true)
    [ -n "$WID" ] && break
    kill -0 "$LOVE_PID" 2>/dev/null || die "the player exited: $(tail -5 "$dir/player.log")"
    sleep 0.2
  done
  [ -n "$WID" ] || die "no player window after 60 s"
  # The HUD's figures change every frame: hidden, the picture settles. (A key sent
  # as the window opens, before the player reads its events, is lost: sent once the
  # first picture has settled.)
  wait_still "$dir"
  xdotool key --window "$WID" h
  wait_still "$dir"
  for edit in added kind operation value; do
    e="$dir/$edit"; mkdir -p "$e"; : > "$e/grabs"
    (cd "$REPO" && luajit tools/fnl.lua tools/edit-window.fnl --edit "$dir/original.fnl" "$edit") \
      > "$dir/next.fnl" || die "cannot make the edit $edit of $s"
    grab "$e" 2.5
    sleep 0.4
    echo "$EPOCHREALTIME" > "$e/save"
    write_scene "$dir/scene.fnl" < "$dir/next.fnl"
    wait "$GRAB_PID" || true; GRAB_PID=""
    (cd "$REPO" && luajit tools/fnl.lua tools/edit-window.fnl "$e" "$dir/frames.log" "$name" "$edit") \
      || status=1
    [ "${KEEP:-0}" = 1 ] || rm -f "$e"/*.xwd
    wait_still "$dir"
  done
  rm -rf "$dir/mesa"
  kill "$LOVE_PID" 2>/dev/null || true
  wait "$LOVE_PID" 2>/dev/null || true
  LOVE_PID=""
done
exit $status
