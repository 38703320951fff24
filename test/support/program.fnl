;; The tape interpreter's program (src/sdf/interpret.fnl) run on the CPU: what the
;; shader's tapeRun does, instruction by instruction, with the descriptors' CPU forms
;; (the ones src/sdf/emit-lua.fnl calls) in double precision. test/interpret_spec.fnl
;; compares it with the tape's own CPU evaluators, so the encoding (opcodes,
;; registers, arguments, loops, guards, a group's rows) is checked under plain LuaJIT,
;; without a GPU.

(local interpret (require :src.sdf.interpret))
(local uniforms (require :src.render.uniforms))

(fn rows-of [tape]
  ;; The interpreter's rows as its strategy sends them, in world coordinates (the
  ;; camera at the origin): the tape's, then the instance bank's. 0-based flat.
  (let [out (uniforms.tape-values tape [0 0 0])]
    (each [_ v (ipairs (uniforms.tape-values tape.instances [0 0 0]))] (table.insert out v))
    out))

(fn runner [o]
  "A function of x y z (and `estimate?`, `materials?`): each object's distance (and
material, a list of its numbers; its exact gradient; whether the program marks it a
half-space) as interpreted object `o` (the :interpreted tape object of a plan)
computes them, with no guard skipping any."
  (let [{: program :set iset : tape} o
        data program.data
        rows (rows-of tape)
        by-code (collect [i e (ipairs iset)] (+ interpret.first-function i -1) e)
        ops interpret.ops
        size (if (= tape.material-size 8) 8 4)
        texel (fn [i] (values (. data (+ 1 (* 4 i))) (. data (+ 2 (* 4 i)))
                              (. data (+ 3 (* 4 i))) (. data (+ 4 (* 4 i)))))]
    (fn arg-index [pc k estimate?]
      (let [(a b c d) (texel (+ pc 2 (math.floor (/ k 2))))]
        (if (= 0 (% k 2)) (if estimate? b a) (if estimate? d c))))
    (fn args-of [pc entry estimate?]
      ;; The call's numbers, flat, as the GLSL reads them.
      (let [out []]
        (var k 0)
        (each [_ a (ipairs entry.args)]
          (when (not a.estimate?)
            (let [i (arg-index pc k estimate?)
                  n (. {:float 1 :vec2 2 :vec3 3 :vec4 4} a.type)]
              (for [j 0 (- n 1)] (table.insert out (. rows (+ i j 1)))))
            (set k (+ k 1))))
        out))
    (fn run [pc end regs estimate? materials?]
      (let [{: D : P : M} regs
            stack []]
        (var pc pc)
        (while (< pc end)
          (let [(op r0 r1 r2) (texel pc)
                (t1 t2 t3 len) (texel (+ pc 1))
                entry (. by-code op)
                args #(args-of pc entry estimate?)]
            (var next-pc (+ pc len))
            (if (= op ops.far) (tset D r0 (math.max (. D r1) (. D r2)))
                (= op ops.divide) (tset D r0 (* (. D r1) t1))
                (= op ops.material)
                (when materials?
                  (let [at (texel (+ pc 2))]
                    (tset M r0 (fcollect [j 1 size] (. rows (+ at j))))))
                (= op ops.cells-end)
                (let [top (. stack (length stack))
                      (_ _ count) (texel (+ r2 1))]
                  (if (> t3 0.5)
                      (let [[qx qy qz] (. P t1) [cx cy cz] (. P t2)]
                        (when (not (and (= qx cx) (= qy cy) (= qz cz)))
                          (tset D r1 (math.min (. D r1) (. D r0)))))
                      (when (< (. D r0) (. D r1))
                        (tset D r1 (. D r0))
                        (when materials? (tset M t2 (. M t1)))))
                  (set top.cell (+ top.cell 1))
                  (if (< top.cell count)
                      (set next-pc r2)
                      (table.remove stack)))
                (let [role entry.role
                      f entry.desc.cpu]
                  (case role
                    :prim (let [[x y z] (. P r1)] (tset D r0 (f x y z (unpack (args)))))
                    :point (let [[x y z] (. P r1)] (tset P r0 [(f x y z (unpack (args)))]))
                    :post (let [[x y z] (. P r2)] (tset D r0 (f (. D r1) x y z (unpack (args)))))
                    :distance (let [[x y z] (. P r2)] (tset D r0 (f (. D r1) x y z (unpack (args)))))
                    :combine (let [a (. D r1) b (. D r2)]
                               (tset D r0 (f a b (unpack (args))))
                               (when materials?
                                 (let [w (entry.desc.cpu-weight a b (unpack (args)))
                                       ma (. M t2) mb (. M t3)]
                                   (tset M t1 (fcollect [j 1 size]
                                                (+ (* (. mb j) (- 1 w)) (* (. ma j) w)))))))
                    :gradient (let [[x y z] (. P r1)]
                                (set regs.gradient [(entry.desc.gradient x y z (unpack (args)))]))
                    :cells (let [top (. stack (length stack))]
                             (when (or (not top) (not= top.pc pc))
                               (table.insert stack {: pc :cell t2})
                               (when (< t2 0.5)
                                 (tset D r0 1e10)
                                 (when materials? (tset M t1 (fcollect [_ 1 size] 0)))))
                             (let [[x y z] (. P r1)]
                               (tset P r2 [(f (. stack (length stack) :cell) x y z (unpack (args)))]))))))
            (set pc next-pc)))))
    (fn [x y z ?estimate? ?materials?]
      (let [(count) (texel 0)]
        (fcollect [k 0 (- count 1)]
          (let [(start end _ grad) (texel (+ 1 (* 3 k)))
                (dout mout _ grad-end) (texel (+ 2 (* 3 k)))
                half-space (texel (+ 3 (* 3 k)))
                regs {:D {} :P {0 [x y z]} :M {}}]
            (run start end regs ?estimate? ?materials?)
            (local gradient
              (when (>= grad 0)
                (let [gregs {:D {} :P {0 [x y z]} :M {}}]
                  (run grad grad-end gregs false false)
                  gregs.gradient)))
            {:d (. regs.D dout) :m (when ?materials? (. regs.M mout)) : gradient
             :half-space? (= half-space 1)}))))))

{: runner}
