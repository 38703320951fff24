#!/bin/sh
# Frame times on a real GPU: the seed scene at 3840x2160 and every showcase scene at
# 1920x1080, each with `love . --bench` (one untimed warm-up frame, then the median of
# FRAMES frames, each drawn and waited for). Run from the project root on a machine
# with a GPU; LOVE names the love binary (default: love).
# Usage: sh tools/gpu-figures.sh [FRAMES]
frames=${1:-60}
love=${LOVE:-love}
"$love" . --bench scenes/seed.fnl --size 3840x2160 --frames "$frames" 2>&1 | tr "\r" "\n" | grep -v "^round"
for s in seed gallery lighting organic flower twisted-tower platonic-shelf machined-part colonnade city spheres; do
  "$love" . --bench "scenes/$s.fnl" --size 1920x1080 --frames "$frames" 2>&1 | tr "\r" "\n" | grep -v "^round"
done
