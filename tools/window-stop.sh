# Sourced by tools/check-states.sh and tools/edit-window.sh: the player (LOVE_PID)
# and the frame grabber (GRAB_PID) they start are stopped when the script ends,
# however it ends.
LOVE_PID=""
GRAB_PID=""
cleanup() {
  [ -n "$GRAB_PID" ] && kill "$GRAB_PID" 2>/dev/null || true
  [ -n "$LOVE_PID" ] && kill "$LOVE_PID" 2>/dev/null || true
  wait 2>/dev/null || true
}
trap cleanup EXIT
