;; What a CPU reference tracer (src/reference.fnl) reads from its scene, plan and
;; options, gathered once: every part of the tracer takes its values from here.

(local emit-lua (require :src.sdf.emit-lua))

(fn settings [scene plan ?options]
  "The settings of a tracer for `scene` lowered to `plan` (see reference.tracer for
the options): the scene and plan, the camera position :cam [x y z], :pixel-angle,
:counts, the render settings (:draw :eps :max-steps :relaxation :hit-test
:normal-method), the view (:view :shaded? :shadows? :glow? :reflections :modern?),
the field :fd (plan.field or nil), the compiled tape's :tape-distance,
:tape-material, :tape-gradient and :tape-estimate (lists by tape number) and :tally (fn [key n]),
which adds n to the counts' key when there are counts."
  (let [options (or ?options {})
        counts options.counts
        render scene.render
        view plan.view
        shaded? (= view :shaded)
        tape (emit-lua.compile plan.tape)]
    {: scene : plan
     :cam (or options.cam-pos [0 0 0])
     :pixel-angle (or options.pixel-angle 0)
     : counts
     :draw render.draw-distance
     :eps render.epsilon
     :max-steps render.max-steps
     :relaxation (if plan.relaxed? render.relaxation 1)
     :hit-test plan.hit-test
     :normal-method (or plan.normals :one-sided)
     : view
     : shaded?
     :shadows? (and shaded? plan.shadows?)
     :glow? (and shaded? plan.glow?)
     :reflections (if (and shaded? plan.reflections?) plan.reflections 0)
     :modern? (or (not= nil plan.lighting) (and plan.tape (= plan.tape.material-size 8)))
     ;; The field (lower.fnl's :field strategy): its grid, when the tape has one.
     :fd plan.field
     :tape-distance tape.distance
     :tape-material tape.material
     :tape-gradient tape.gradient
     :tape-estimate tape.estimate
     :tally (fn [key n]
              (when counts (tset counts key (+ (or (. counts key) 0) n))))}))

{: settings}
