#!/bin/sh
# The tape interpreter against the compiled shader on a real GPU (issue 42): for each
# scene, `love . --bench` of the compiled shader and of the interpreter's (--interpret:
# the catalogue of every kind, as the player holds it), the driver's shader cache off
# (NVIDIA's and Mesa's), so newShader is a compile; then the interpreter's shader
# compiled again with a cache (the player's second start, or any later edit). Run
# from the project root; LOVE names the love binary (default: love).
# Usage: sh tools/interpret-figures.sh [SIZE] [FRAMES] [SCENE...]
size=${1:-1280x720}
frames=${2:-10}
shift 2 2>/dev/null
scenes=${*:-"organic twisted-tower flower lighting machined-part platonic-shelf"}
love=${LOVE:-love}
run() {
  timeout 120 "$love" . --bench "scenes/$1.fnl" --size "$size" --frames "$frames" $2 2>&1 \
    | tr "\r" "\n" | grep -E "^(renderer|scenes|shader|error)"
}
for s in $scenes; do
  echo "== $s compiled"
  __GL_SHADER_DISK_CACHE=0 MESA_SHADER_CACHE_DISABLE=true run "$s"
  echo "== $s interpreted"
  __GL_SHADER_DISK_CACHE=0 MESA_SHADER_CACHE_DISABLE=true run "$s" --interpret
done
# The first scene's interpreter twice with an empty cache: the second is a start of
# the player after the first (the same shader, from the cache).
cache=$(mktemp -d)
first=${scenes%% *}
for turn in 1 2; do
  echo "== $first interpreted, cache $cache, turn $turn"
  __GL_SHADER_DISK_CACHE_PATH=$cache MESA_SHADER_CACHE_DIR=$cache run "$first" --interpret
done
rm -rf "$cache"
