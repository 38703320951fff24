;; The scene worker under plain LuaJIT (src/scene/worker.fnl starts it so when LÖVE
;; is not running: tests and tools): `luajit tools/fnl.lua tools/scene-worker.fnl`.
((. (require :src.scene.worker-main) :serve!) io.stdin io.stdout)
