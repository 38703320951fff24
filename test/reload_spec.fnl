;; Hot reload in the running app (headless): `love . --soak` edits a scene file on disk
;; and goes through the player's own watcher and reload path. Each cycle checks what a
;; player sees: a value edit changes the next frame with no shader compile, a structural
;; edit compiles, a broken file keeps the last image and reports file:line, the next
;; good edit clears it, a file that another process writes in two halves 50 ms apart
;; and a load reads between them shows no error and loads whole. Over 1000 edits Lua
;; memory and live shaders stay flat.
(local app (require :test.support.app))

(describe "hot reload in the app"
  (fn []
    (it "survives 1000 value, structural and broken edits with flat memory and shaders"
      (fn []
        (let [(code out) (app.love "--soak --cycles 1000" {:timeout 300})]
          (print)
          (each [line (out:gmatch "[^\n]+")]
            (when (line:match "^[a-zA-Z ]+[:(]") (print line)))
          (assert.truthy (out:find "soak: 1000 edits (334 value, 333 structural, 333 broken)" 1 true) out)
          (assert.truthy (out:find "soak checks: 0 failed" 1 true) out)
          (let [(_ checks) (out:gsub "reload check, scenes/seed.fnl: [^\n]*: ok" "")]
            (assert.are.equal 7 checks out))
          (assert.are.equal 0 code out)
          (let [(warm final) (out:match "Lua memory after cycle %d+: (%d+) KB, at the end: (%d+) KB")]
            (assert.truthy warm out)
            ;; Flat: within 10% of the warmed-up figure (the GC's own slack).
            (assert.is_true (< (tonumber final) (* 1.1 (tonumber warm)))))
          (let [(warm final) (out:match "live shaders after cycle %d+: (%d+), at the end: (%d+)")]
            (assert.are.equal warm final)))))

    ;; The scripted edits must work on any scene: gallery builds its object list in
    ;; code (`:objects ring`), organic writes `:objects` and its list on two lines and
    ;; is a scene tree, colonnade has no coloured sphere.
    (each [_ name (ipairs [:gallery :organic :colonnade])]
      (it (.. "passes its reload checks on scenes/" name ".fnl")
        (fn []
          (let [(code out) (app.love (.. "--soak scenes/" name ".fnl --cycles 6") {:timeout 300})]
            (assert.truthy (out:find "soak checks: 0 failed" 1 true) out)
            (assert.are.equal 0 code out)))))))
