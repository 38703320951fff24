;; tier: fast
;; Lowering scene trees to the tape, and what the emitters make of it: only what a
;; scene uses reaches the shader, the output is deterministic, the structure key
;; tells value edits from structural ones, classes and Lipschitz factors per node.

(local load (require :src.scene.load))
(local plan-mod (require :src.render.plan))
(local codegen (require :src.render.codegen))
(local uniforms (require :src.render.uniforms))
(local lower (require :src.sdf.lower))
(local camera (require :src.render.camera))

(fn plan-of [objects-text]
  (let [(s err) (load.load-string (.. "{:objects [" objects-text "]}") "t.fnl")]
    (assert s err)
    (values (assert (plan-mod.scene->plan s)) s)))

(fn shader-of [objects-text]
  (assert (codegen.shader (plan-of objects-text) :core)))

(describe "the tape"
  (fn []
    (it "puts only the functions a scene uses into its shader"
      (fn []
        (let [text (shader-of "{:kind :union :children [{:kind :sphere :pos [1 0 0]} {:kind :torus}]}")]
          (assert.truthy (text:find "float sdTorus(" 1 true))
          (assert.truthy (text:find "float opUnion(" 1 true))
          (assert.falsy (text:find "opTwist" 1 true))
          (assert.falsy (text:find "sdOctahedron" 1 true))
          (assert.falsy (text:find "opSmoothUnion" 1 true)))
        (let [text (shader-of "{:kind :twist :children [{:kind :octahedron}]}")]
          (assert.truthy (text:find "vec3 opTwist(" 1 true))
          (assert.truthy (text:find "float opTwistDistance(" 1 true))
          (assert.falsy (text:find "opUnion" 1 true)))))

    (it "holds every object, a field's too: a strategy of the tape, drawn by its emitters"
      (fn []
;; 20 flat spheres (a field), 20 mirrored ones (a group with a grid) and a
        ;; mirrored torus (written out: a torus placed and coloured alone would join
        ;; the field as a marched member).
        (let [spheres (fn [mirror]
                        (table.concat (fcollect [i 1 20]
                                        (string.format "{:kind :sphere :pos [%d %d 1] :radius 0.4%s}"
                                                       (* 2 (% i 5)) (* 2 (math.floor (/ i 5)))
                                                       (if mirror " :mirror 0.5" "")))
                                      " "))
              (p s) (plan-of (.. (spheres false) " " (spheres true) " {:kind :torus :pos [30 0 1] :mirror 0.5}"))
              [first second third] p.tape.objects
              text (assert (codegen.shader p :core))
              emit-lua (require :src.sdf.emit-lua)
              tape (emit-lua.compile p.tape)]
          (assert.are.equal 20 (?. first :field :count))
          (assert.are.equal 20 (?. second :instances :count))
          (assert.is_truthy third.leaf)
          ;; Every object is numbered once, the field's first.
          (assert.are.equal 41 p.tape.count)
          (assert.are.equal 41 (length p.objects))
          (for [i 1 20] (assert.are.equal (. s.objects i) (. p.objects i)))
          (assert.are.equal (. s.objects 41) (. p.objects 41))
          ;; The field's part of each function comes from the tape's emitter.
          (assert.is_truthy (text:find "d = min(d, fieldMap(p, -1, best));" 1 true))
          (assert.is_truthy (text:find "if (gObject >= 0 && gObject < 20) return fieldNormal(p, gObject);" 1 true))
          ;; The Lua emitter gives each member the round box's distance and the box's
          ;; gradient: here a sphere's, |q - c| - r and (q - c) / |q - c|.
          (for [i 1 20]
            (let [[cx cy cz] (. s.objects i :pos)
                  (x y z) (values (+ cx 0.3) (- cy 0.7) (+ cz 1.1))
                  len (math.sqrt (+ (* 0.3 0.3) (* 0.7 0.7) (* 1.1 1.1)))
                  (nx _ nz) ((. tape.gradient i) x y z)]
              (assert.is_true (< (math.abs (- ((. tape.distance i) x y z) (- len 0.4))) 1e-12))
              (assert.is_true (< (math.abs (- nx (/ 0.3 len))) 1e-12))
              (assert.is_true (< (math.abs (- nz (/ 1.1 len))) 1e-12)))))))

    (it "draws the article's flat objects as tree leaves: one path, whatever their fields"
      (fn []
        (let [flat (plan-of "{:kind :sphere :pos [1 2 3] :radius 2} {:kind :plane :height 1}")
              tree (plan-of "{:kind :sphere :pos [1 2 3] :radius 2 :mirror 1} {:kind :plane :height 1 :normal [0 0 1]}")]
          (assert.are.equal 2 (length flat.tape.objects))
          (assert.are.equal flat.key tree.key)
          (assert.are.equal (codegen.shader flat :core) (codegen.shader tree :core)))
        ;; A mirror amount is a value: the same code.
        (assert.are.equal (. (plan-of "{:kind :sphere :mirror 0.5}") :tape :key)
                          (. (plan-of "{:kind :sphere}") :tape :key))))

    (it "lowers nested twists in work that grows with their depth, not 2^depth"
      (fn []
        ;; Each twist lowers its child aside for its bounds; that result is now kept
        ;; for the rest of the lowering. Before, 14 deep took 0.19 s and each level
        ;; doubled it: 30 deep would not have finished.
        (var node "{:kind :box :size [1 1 1]}")
        (for [_ 1 30] (set node (.. "{:kind :twist :angle 5 :children [" node "]}")))
        (let [(p s) (plan-of node)]
          (assert.is_truthy s)
          ;; One object whose code has a twist step per level.
          (let [code (. p.tape.objects 1 :code)
                twists (icollect [_ step (ipairs code)] (when (and (= step.op :point) (: (tostring step.desc.glsl-name) :find "wist")) step))]
            (assert.are.equal 30 (length twists))))))

    (it "is deterministic, and its key changes with structure, not with values"
      (fn []
        (let [a "{:kind :smooth-union :radius 0.3 :children [{:kind :sphere :color [1 0 0]} {:kind :box :pos [1 0 0]}]}"
              b "{:kind :smooth-union :radius 0.7 :children [{:kind :sphere :color [0 1 0]} {:kind :box :pos [2 0 0]}]}"
              c "{:kind :smooth-union :kernel :exp :radius 0.3 :children [{:kind :sphere} {:kind :box :pos [1 0 0]}]}"
              d "{:kind :union :children [{:kind :sphere} {:kind :box :pos [1 0 0]}]}"]
          (assert.are.equal (shader-of a) (shader-of a))
          (assert.are.equal (. (plan-of a) :key) (. (plan-of b) :key))
          (assert.are.equal (shader-of a) (shader-of b))
          (assert.are_not.equal (. (plan-of a) :key) (. (plan-of c) :key))
          (assert.are_not.equal (. (plan-of a) :key) (. (plan-of d) :key)))))

    (it "sends tree parameters in uTape, the outermost translation camera-relative"
      (fn []
        (let [(p s) (plan-of "{:kind :sphere :radius 2 :pos [100 200 300] :mirror 0.5}")
              cam (doto (camera.from-scene s) (tset :pos [90 190 290]))
              us (uniforms.pack s p cam 64 48)
              tape (accumulate [found nil _ u (ipairs us)] (or found (and (= u.name "uTape") u)))]
          (assert.truthy tape)
          ;; Row 0: the translation, minus the camera, and the radius; then the
          ;; material. (Read once per pixel, the rows are a texture's texels.)
          (let [rows tape.texture.data]
            (assert.are.same [10 10 10 2] [(. rows 1) (. rows 2) (. rows 3) (. rows 4)])
            (assert.are.same [1 1 1 0.5] [(. rows 5) (. rows 6) (. rows 7) (. rows 8)])))))

    (it "knows each node's class, Lipschitz factor and bounds"
      (fn []
        (let [p (plan-of "{:kind :union :children [{:kind :twist :angle 90 :children [{:kind :box :size [2 2 4]}]} {:kind :displace :amplitude 0.1 :frequency 10 :children [{:kind :sphere}]} {:kind :sphere :pos [5 0 0]}]}")
              lines (lower.describe p.tape)
              text (table.concat lines "\n")]
          ;; The implicit translation (shorthand), then the union and its children.
          (assert.truthy (text:find "union  bound  " 1 true) text)
          (assert.truthy (text:find "twist  bound, Lipschitz 2.61" 1 true) text)
          (assert.truthy (text:find "box  exact  bounds ±1 ±1 ±2  objects[1].children[1].children[1]" 1 true) text)
          (assert.truthy (text:find "displace  bound, Lipschitz 2.73" 1 true) text)
          (assert.truthy (text:find "sphere  exact  bounds ±1 ±1 ±1" 1 true) text))))

    (it "divides a displaced distance by its Lipschitz factor in both evaluators"
      (fn []
        (let [text (shader-of "{:kind :displace :amplitude 0.1 :frequency 10 :children [{:kind :sphere}]}")]
          (assert.truthy (text:find "* 0.366025404;  // Lipschitz 2.73205" 1 true) text))))))
