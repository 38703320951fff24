#!/bin/sh
# How long the player takes to show an edit of each showcase scene (love . --edit-latency:
# a structural edit when idle, a value edit, a structural edit while the still is
# built and one while its bands are drawn), with the compile helper (the default) and
# compiling in the player (--sync-compile), alternating, each run with an empty
# shader cache of its own (the helper's gain is the cache). Runs headless (SDL's
# offscreen driver) unless DISPLAY is set; LOVE names the love binary.
#
# BASE=DIR runs the player of DIR (another checkout, holding this checkout's
# src/app/edit-latency.fnl) before this one for each scene and mode: before and after
# in one interleaved run, each line prefixed with "before" or "after". SYNC=0 leaves
# out the --sync-compile runs. EDIT_LATENCY_LIMIT=S: an edit not shown after S
# seconds is reported as such (default 600; a player that loses an edit waits that).
# Usage: sh tools/edit-latency.sh [SCENE...]   (from the project root)
love=${LOVE:-love}
scenes=${*:-"scenes/gallery.fnl scenes/lighting.fnl scenes/twisted-tower.fnl scenes/machined-part.fnl scenes/organic.fnl scenes/platonic-shelf.fnl scenes/flower.fnl scenes/colonnade.fnl"}
[ -n "$DISPLAY" ] || export SDL_VIDEODRIVER=offscreen
here=$(pwd)
modes='helper'
[ "${SYNC:-1}" = 0 ] || modes='helper --sync-compile'
cache=$(mktemp -d)
trap 'rm -rf "$cache"' EXIT
for s in $scenes; do
  for mode in $modes; do
    [ "$mode" = helper ] && mode=
    for dir in ${BASE:+"$BASE"} "$here"; do
      label=""
      [ -n "$BASE" ] && { [ "$dir" = "$here" ] && label="after: " || label="before: "; }
      rm -rf "$cache/mesa"
      (cd "$dir" && MESA_SHADER_CACHE_DIR="$cache/mesa" "$love" . --edit-latency "$here/$s" $mode 2>&1) \
        | grep "shown after" | sed "s|$here/||; s|^|$label|"
    done
  done
done
