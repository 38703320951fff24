;; tier: fast
;; The functions a mesh calls for every point, vertex or pair of triangles make no
;; garbage (issue 46: the mesher's speed). A table or a closure made per call costs
;; the collector's time, and a closure made in a loop stops LuaJIT from compiling it
;; ("NYI: bytecode 51", FNEW): before, machined-part's vertex colours took 12
;; microseconds each, 85% of it interpreted, against 2.3 after. What is measured is
;; the heap's growth over many calls with the collector stopped, so the verdict does
;; not depend on the machine's speed or on what LuaJIT compiles.

(local load (require :src.scene.load))
(local plan-mod (require :src.render.plan))
(local emit-lua (require :src.sdf.emit-lua))
(local reference (require :src.reference))
(local mesh-scene (require :src.mesh.scene))
(local intersect (require :src.mesh.intersect))

(local calls 2000)

(fn garbage-per-call [f]
  "Bytes the heap grows by per call of `f`, the collector stopped meanwhile: the
least of five rounds (LuaJIT's compiled traces are objects on the heap too, made in
the first rounds)."
  (var least math.huge)
  (for [_ 1 5]
    (collectgarbage :collect)
    (collectgarbage :stop)
    (let [before (collectgarbage :count)]
      (for [_ 1 calls] (f))
      (set least (math.min least (/ (* 1024 (- (collectgarbage :count) before)) calls))))
    (collectgarbage :restart))
  least)

;; Under a byte a call: what the loop itself may leave (nothing, in practice); one
;; table is 32 bytes or more, a closure 20 or more.
(local limit 1)

(fn finite-scene [path]
  (. (mesh-scene.select-objects (assert (load.load-file path))) :scene))

(describe "what a mesh evaluates per point makes no garbage"
  (fn []
    (it "the tape's distance and material functions (machined-part's bracket has 30 instructions)"
      (fn []
        (let [scene (finite-scene "scenes/machined-part.fnl")
              plan (assert (plan-mod.scene->plan scene {:view :glow :probe? true}))
              c (emit-lua.compile plan.tape)]
          (each [_ what (ipairs [:distance :material])]
            (each [i f (ipairs (. c what))]
              (let [g (garbage-per-call (fn [] (f 0.3 0.2 0.9)))]
                (assert.is_true (< g limit)
                                (string.format "%s function of object %d: %.1f bytes a call"
                                               what i g))))))))
    (it "the reference's map-color (a mesh's vertex colours)"
      (fn []
        (each [_ path (ipairs ["scenes/machined-part.fnl" "scenes/organic.fnl"])]
          (let [scene (finite-scene path)
                plan (assert (plan-mod.scene->plan scene {:view :glow :probe? true}))
                T (reference.tracer scene plan)
                g (garbage-per-call (fn [] (T.map-color 0.3 0.2 0.9)))]
            (assert.is_true (< g limit) (string.format "%s: %.1f bytes a call" path g))))))
    (it "the exact test of a pair of triangles, for pairs apart or sharing a vertex"
      (fn []
        ;; Most pairs the broad phase gives are neighbours around a vertex, each
        ;; on one side of the other's plane: they end at the plane test.
        (let [p [0 0 0 1 0 0 0 1 0]
              apart [0 0 1 1 0 1 0 1 1]
              around [0 0 0 -1 0 0.2 0 -1 0.3]]
          (each [name q (pairs {: apart : around})]
            (assert.are.equal 0 (intersect.pair-overlap p q))
            (let [g (garbage-per-call (fn [] (intersect.pair-overlap p q)))]
              (assert.is_true (< g limit) (string.format "%s: %.1f bytes a call" name g)))))))))
