;; tier: fast
;; The GLSL forms of mirrors and rotations that only move the axes about
;; (src/sdf/operations.fnl: mirror-axes, rotate-permutation): a mirror across a plane
;; of the axes as one abs, a quarter-turn rotation as three products. The GPU runs
;; them; the CPU evaluator keeps the general forms. Here each form's GLSL return
;; expression, read back into Lua, against the CPU form on points around.

(local scene-load (require :src.scene.load))
(local plan-mod (require :src.render.plan))
(local codegen (require :src.render.codegen))
(local operations (require :src.sdf.operations))
(local {: lcg} (require :test.support.fields))

(fn plan-of [node-text]
  (let [(scene err) (scene-load.load-string (.. "{:objects [" node-text "]}") "axes.fnl")]
    (assert scene err)
    (assert (plan-mod.scene->plan scene {:far-field? false}))))

(fn glsl->lua [form names]
  "The form's GLSL return expression as a Lua function of x y z and the packed
arguments (`names`, in order: each vec3 argument's three components)."
  (let [expr (assert (form.glsl:match "return vec3%((.*)%);") form.glsl-name)
        lua-expr (-> expr
                     (: :gsub "abs%(" "math.abs(")
                     (: :gsub "(%a%d?)%.([xyz])" "%1_%2"))
        args (table.concat names ", ")]
    (assert (load (.. "return function(p_x, p_y, p_z, " args ") return " lua-expr " end")))))

(fn points [n seed]
  (let [rand (lcg seed)]
    (fcollect [_ 1 n] (fcollect [_ 1 3] (* 4 (- (* 2 (rand)) 1))))))

(fn close? [a b] (< (math.abs (- a b)) 1e-12))

(describe "axis forms"
  (fn []
    (it "mirrors across a plane of the axes by one abs, as the general form does"
      (fn []
        (let [mirror (operations.lookup :mirror)]
          (each [_ n (ipairs [[1 0 0] [-1 0 0] [0 1 0] [0 -1 0] [0 0 1] [0 0 -1]])]
            (let [form (operations.variant mirror {:normal n})
                  f ((glsl->lua form ["n_x" "n_y" "n_z"]))]
              (assert.are_not.equal mirror form)
              (each [_ [x y z] (ipairs (points 50 3))]
                (let [(ex ey ez) (form.cpu x y z (table.unpack n))
                      (gx gy gz) (f x y z (table.unpack n))]
                  (assert.is_true (and (close? ex gx) (close? ey gy) (close? ez gz))
                                  (.. (table.concat n " ") ": " gx " " gy " " gz))))))
          ;; Not across another plane.
          (assert.are.equal mirror (operations.variant mirror {:normal [0.6 0.8 0]}))
          (let [text (assert (codegen.shader (plan-of "{:kind :mirror :normal [0 1 0] :children [{:kind :sphere :pos [1 1 0]}]}") :core))]
            (assert.truthy (text:find "opMirrorY(" 1 true))
            (assert.falsy (text:find "vec3 opMirror(" 1 true))))))

    (it "turns by quarter turns with three products, as the matrix does"
      (fn []
        (let [rotate (operations.lookup :rotate)
              seen {}]
          (for [ax 0 3] (for [ay 0 3] (for [az 0 3]
            (let [o {:angles [(* 90 ax) (* 90 ay) (* 90 az)]}
                  form (operations.variant rotate o)
                  rows (rotate.pack o)
                  f ((glsl->lua form ["r0_x" "r0_y" "r0_z" "r1_x" "r1_y" "r1_z" "r2_x" "r2_y" "r2_z"]))]
              (assert.are_not.equal rotate form)
              (tset seen form.glsl-name true)
              (each [_ [x y z] (ipairs (points 20 5))]
                (let [(ex ey ez) (form.cpu x y z (table.unpack rows))
                      (gx gy gz) (f x y z (table.unpack rows))]
                  (assert.is_true (and (close? ex gx) (close? ey gy) (close? ez gz))
                                  (.. (table.concat o.angles " ") ": " gx " " gy " " gz))))))))
          ;; The six orders of the axes.
          (assert.are.equal 6 (accumulate [n 0 _ (pairs seen)] (+ n 1)))
          ;; A turn between the axes keeps the matrix.
          (assert.are.equal rotate (operations.variant rotate {:angles [0 45 0]}))
          (assert.are.equal rotate (operations.variant rotate {:axis [1 1 0] :angle 90 :angles [0 0 0]}))
          ;; Which axes is structure, the signs are values: another order is
          ;; another key, a turn the other way the same.
          (let [key #(. (plan-of (.. "{:kind :rotate :angles " $ " :children [{:kind :box :size [1 2 3]}]}")) :tape :key)]
            (assert.are.equal (key "[0 90 0]") (key "[0 -90 0]"))
            (assert.are_not.equal (key "[0 90 0]") (key "[0 0 90]"))
            (assert.are_not.equal (key "[0 90 0]") (key "[0 45 0]"))))))))
