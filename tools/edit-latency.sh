#!/bin/sh
# How long the player takes to show an edit of each showcase scene, with the compile
# helper (the default) and compiling in the player (--sync-compile), alternating, each
# run with an empty shader cache of its own (the helper's gain is the cache). Runs
# headless (SDL's offscreen driver) unless DISPLAY is set; LOVE names the love binary.
# Usage: sh tools/edit-latency.sh [SCENE...]   (from the project root)
love=${LOVE:-love}
scenes=${*:-"scenes/gallery.fnl scenes/lighting.fnl scenes/twisted-tower.fnl scenes/machined-part.fnl scenes/organic.fnl scenes/platonic-shelf.fnl scenes/flower.fnl scenes/colonnade.fnl"}
[ -n "$DISPLAY" ] || export SDL_VIDEODRIVER=offscreen
cache=$(mktemp -d)
trap 'rm -rf "$cache"' EXIT
for s in $scenes; do
  for mode in "" --sync-compile; do
    rm -rf "$cache/mesa"
    MESA_SHADER_CACHE_DIR="$cache/mesa" "$love" . --edit-latency "$s" $mode 2>&1 | grep "shown after"
  done
done
