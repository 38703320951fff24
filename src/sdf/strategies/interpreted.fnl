;; The interpreted strategy: a whole tape run by the tape interpreter (src/sdf/
;; interpret.fnl), one shader for every tape of its instruction set. Its one tape
;; object stands for the tape's objects (its :tape), numbered as they are; the CPU
;; evaluators, bounds and the reference's queries (its :members) are theirs. See
;; src/sdf/strategies.fnl for the interface.

(local glsl (require :src.sdf.emit-glsl))
(local emit-lua (require :src.sdf.emit-lua))
(local interpret (require :src.sdf.interpret))

(fn members [o] o.tape.objects)

(fn strategy [m]
  ;; A member's own strategy (a tree's; see interpret.refusal).
  ((. (require :src.sdf.strategies) :of) m))

(fn selected [first]
  ;; A condition: gObject is one of the program's objects (their count is the
  ;; program's, not in the text: any tape of the set draws with the same shader).
  (.. "gObject >= " first " && gObject < " first " + int(tapeCode(0).x)"))

(fn number [first o]
  ;; The number in gObject of its first object: after a field's members (their
  ;; count a uniform: see interpret.tape-of), or `first`.
  (if (not o.after-field?) (+ first o.id)
      (= first 0) "uFieldCount"
      (.. first " + uFieldCount")))

(fn color-term [_ o ?first mirrors? modern?]
  (let [mt (if modern? "mat2x4" "vec4")
        row (if modern? "tapeMaterial[0]" "tapeMaterial")]
    ["{  // every object, by the interpreter"
     (glsl.indented
      [(.. mt " tapeMaterial;")
       "int tapeObject;"
       "float tapeD = tapeColor(p, d, tapeMaterial, tapeObject);"
       (.. "if (tapeObject >= 0) { d = tapeD; color = " row ".rgb;"
           (if (or mirrors? modern?) (.. " gMirror = " row ".a;") "")
           (if modern? " gMaterial = tapeMaterial[1];" "")
           (if ?first (.. " gObject = " (number ?first o) " + tapeObject;") "") " }")])
     "}"]))

{:name :interpreted
 :doc "a whole tape run by the interpreter shader (no compile for a new tape of its set)"
 ;; Its objects are its tape's, each counted by its own strategy (a group's members
 ;; one each).
 :count (fn [o] (accumulate [n 0 _ m (ipairs (members o))] (+ n ((. (strategy m) :count) m))))
 :folds? false
 :marched? (fn [_] true)
 :infos (fn [o] (let [out []]
                  (each [_ m (ipairs (members o))]
                    (each [_ info (ipairs (or ((. (strategy m) :infos) m) []))]
                      (table.insert out info)))
                  out))
 :describe (fn [o] (.. " (" (length o.set) " functions)"))
 :glsl {:distance (fn [cx _]
                    ;; In mapFinite (cx.finite?), not the half-spaces: planesHit meets them;
                    ;; in mapSome, where its expression says (emit-glsl.some-terms).
                    [(.. "d = tapeMin(p, d, -1, -1, "
                         (case cx.finite? true "true" (where expr (= (type expr) :string)) expr _ "false")
                         ");  // every object, by the interpreter")])
        :color color-term
        ;; With `materials`, mapColor's term.
        :object (fn [_ o first mirrors? modern?]
                  (let [n (number first o)
                        minus #(if (= n 0) $ (.. $ " - " n))]
                    (glsl.either-terms
                     (color-term nil o first mirrors? modern?)
                     [(.. "d = tapeMin(p, d, all ? -1 : " (minus "only") ", skip < 0 ? -1 : "
                          (minus "skip") ", false);")])))
        :gradient (fn [_ o first action]
                    ;; Written as the set says (the text is the set's alone); the
                    ;; program says which objects have one (tapeExact).
                    (let [n (number first o)]
                      (when (accumulate [any? false _ e (ipairs o.set)]
                              (or any? (= e.role :gradient)))
                        [(.. "if (" (selected n) " && tapeExact(gObject - " n ")) {")
                         (.. "    " action "tapeGradient(p, gObject - " n ");")
                         "}"])))
        ;; Any program may hold half-spaces: the program says which (tapeHalfSpace).
        :planes (fn [_ _] ["t = tapePlanesHit(p, rd, t);  // the half-spaces, by the interpreter"])
        :exact? (fn [o] (accumulate [all? true _ m (ipairs (members o))]
                          (and all? (glsl.leaf-exact? m))))}
 :lua (fn [_ o what _ into]
        (let [banks (emit-lua.banks o.tape)
              sources (icollect [_ m (ipairs (members o))]
                        ((. (strategy m) :lua) o.tape m what banks into))]
          (when (> (length sources) 0) (table.concat sources "\n"))))
 :spheres (fn [plan o at out]
            (accumulate [at at _ m (ipairs (members o))]
              ((. (strategy m) :spheres) plan m at out)))
 ;; The CPU reference queries its objects each (strategies.queried).
 :members members
 :uniforms (fn [plan o cam-pos]
             ;; The tape's rows (camera-relative where they hold positions) and the
             ;; program, each an rgba32f image.
             ;; The tape's rows, then the instance bank's (interpret.members-of).
             (let [uniforms (require :src.render.uniforms)
                   data (uniforms.tape-values o.tape cam-pos)
                   _ (each [_ v (ipairs (uniforms.tape-values o.tape.instances cam-pos))]
                       (table.insert data v))
                   rows (/ (length data) 4)
                   prog o.program]
               [{:name "uTape" :type :texture :count rows
                 :texture {:width (math.max 1 (math.min rows interpret.width))
                           :height (math.max 1 (math.ceil (/ rows interpret.width)))
                           : data}}
                {:name "uProgram" :type :texture
                 :texture {:width prog.width :height prog.height :data prog.data}}]))
 ;; The exact gradients its set holds, then the interpreter (its chunk).
 :shader {:functions (fn [plan o fill defined]
                       (let [gradients (icollect [_ e (ipairs o.set)]
                                         (when (= e.role :gradient) {:leaf {:prim {:desc e.desc}}}))]
                         [(glsl.gradient-functions {:objects gradients} #true defined)
                          (fill "shaders/strategies/interpreted.glsl"
                                (interpret.shader-slots o.set plan.tape.material-size))]))}}
