#!/usr/bin/env bash
# `make dist`: dist/fennel-raymarcher.love, the game folder zipped with Fennel inside,
# so `love dist/fennel-raymarcher.love [SCENE | --render SCENE --out X.png ...]` runs on
# a machine that has only LÖVE. Scenes given by path are read from the working
# directory; the bundled ones (scenes/..., examples/...) from inside the archive.
set -euo pipefail
cd "$(dirname "$0")/.."
name=fennel-raymarcher
fennel_lua=""
for f in lib/fennel.lua /usr/share/lua/5.4/fennel.lua /usr/share/lua/5.3/fennel.lua; do
  if [ -f "$f" ]; then fennel_lua=$f; break; fi
done
if [ -z "$fennel_lua" ]; then
  echo "make dist: fennel.lua not found (run make deps first)" >&2
  exit 1
fi
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
cp -r main.fnl conf.lua src shaders scenes examples "$stage"/
# The compiled Lua (make dist builds it first): the archive starts without compiling.
luajit tools/build-lua.lua --quiet
mkdir -p "$stage/build" && cp -r build/lua "$stage/build/"
# At the archive's root, where LÖVE's own module searcher finds it.
cp "$fennel_lua" "$stage/fennel.lua"
mkdir -p dist
rm -f "dist/$name.love"
(cd "$stage" && zip -qr -X "$OLDPWD/dist/$name.love" .)
echo "wrote dist/$name.love ($(du -k "dist/$name.love" | cut -f1) KB, Fennel from $fennel_lua)"
