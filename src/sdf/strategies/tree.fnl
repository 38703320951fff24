;; The tree strategy: one scene object's lowered tree, written out in the shader as
;; its own code (lower.fnl's objects). A half-space (a leaf solid below a plane) is
;; met in closed form by a bounded march. See src/sdf/strategies.fnl for the
;; interface.

(local glsl (require :src.sdf.emit-glsl))
(local emit-lua (require :src.sdf.emit-lua))
(local bounds (require :src.render.bounds))
(local runs (require :src.reference.distance))

(fn block [cx o first materials? open tail]
  ;; The object's comment and its block in a minimum (glsl.object-body).
  [(glsl.object-comment o) (glsl.object-body cx o (tostring (+ first o.id)) materials? open tail)])

(fn selected [cx o first lines-fn]
  ;; `(lines-fn cx)`, run when gObject is the object's number.
  [(.. "if (gObject == " (+ first o.id) ") {  " (glsl.object-comment o))
   (glsl.indented (lines-fn cx))
   "}"])

{:name :tree
 :doc "one object's tree, written out in the shader"
 :takes? (fn [_] true)
 :rank 100
 :gathers? false
 :key (fn [key _] key)
 :count (fn [_] 1)
 :folds? true
 :marched? (fn [o] (not o.half-space?))
 :infos (fn [o] [o.info])
 :describe (fn [_] "")
 :glsl (doto (glsl.written-terms block selected)
         ;; Its code once for mapObject's every query: its materials computed only
         ;; for the colour query, where it is the nearest so far (glsl.either-tail).
         (tset :object (fn [cx o first mirrors? modern?]
                         [(block cx o first (not (glsl.deferred-materials? o)) glsl.taken-open
                                 (glsl.either-tail cx o mirrors? modern?))]))
         (tset :planes (fn [cx o]
                         (when o.half-space?
                           [(glsl.object-comment o) ((glsl.plane-block o) cx)]))))
 :lua (fn [tape o what banks into] (emit-lua.object-evaluators tape o what banks into))
 :spheres (fn [plan o at out]
            (let [at (+ at 1)]
              (when (not o.half-space?)
                (table.insert out (or (bounds.object-sphere (. plan.objects at) o.info) false)))
              at))
 :run (fn [_ _ run] run)
 :reference {:min runs.each-min :color runs.each-color :near runs.each-near}}
