;; tier: fast
;; Fields (src/render/field.fnl): many spheres and boxes in textures, found through a
;; grid. The grid's lists, its distance queries and the reference's march through it
;; are checked against brute force over every object (the oracle).

(local scene (require :src.scene.load))
(local plan (require :src.render.plan))
(local camera (require :src.render.camera))
(local codegen (require :src.render.codegen))
(local uniforms (require :src.render.uniforms))
(local export (require :src.render.export))
(local reference (require :src.reference))
(local compare (require :src.verify.compare))
(local field (require :src.render.field))
(local {: marched-mix} (require :test.support.scenes))
(local ffi (require :ffi))

(fn f32 [x]
  ;; `x` rounded to float32, as a float texture holds it.
  (. (ffi.new "float[1]" x) 0))

(fn shapes-of [fd]
  ;; The field's round boxes as a list of [cx cy cz hx hy hz r] (see field.shape-at).
  (fcollect [i 1 fd.count] [(field.shape-at fd i)]))

(fn scattered [n ?extra ?render ?spheres-only?]
  ;; A scene of n spheres and boxes (alternating; only spheres when asked)
  ;; scattered over a 40 x 40 x 10 region above a floor, by the scene's own
  ;; generator.
  (assert (scene.load-string
           (.. "(var seed 7)
(fn rnd [] (set seed (% (+ (* seed 1103515245) 12345) 2147483648)) (/ seed 2147483648))
(local objects [{:kind :plane :height 0 :color [0.6 0.6 0.6]} " (or ?extra "") "])
(for [i 1 " n "]
  (let [x (+ -20 (* 40 (rnd))) y (+ -20 (* 40 (rnd))) z (+ 0.5 (* 10 (rnd)))
        r (+ 0.2 (* 0.5 (rnd)))
        color [(rnd) (rnd) (rnd)]]
    (table.insert objects (if (and (= 0 (% i 2)) " (if ?spheres-only? "false" "true") ")
                              {:kind :box :pos [x y z] :size [r (* 2 r) r] : color}
                              {:kind :sphere :pos [x y z] :radius r : color}))))
{:camera {:pos [0 -35 12] :yaw 90 :pitch 15 :fov 60}
 :light {:pos [-20 -30 40]}
 :render " (or ?render "{:shadows true :reflections 1 :relaxation 1}") "
 :objects objects}")
           "t.fnl")))

(fn against-brute-force [s n]
  ;; The reference's results on n pixels of a 160x90 image of scene `s` with its
  ;; field, and brute force's: the same scene without one, every object marched at
  ;; every step. Returns the field's plan and both result lists.
  (let [cam (camera.from-scene s)
        pf (assert (plan.scene->plan s))
        pb (assert (plan.scene->plan s {:field? false :grids? false :uniform-limit 1e6}))
        pixels (fcollect [i 0 (- n 1)] [(% (* i 37) 160) (% (* i 53) 90)])]
    (values pf (reference.render-pixels s pf cam 160 90 pixels)
            (reference.render-pixels s pb cam 160 90 pixels))))

(fn points [n ?seed]
  ;; n points spread over the region and a little around it (a fixed sequence).
  (var seed (or ?seed 3))
  (fn rnd [] (set seed (% (+ (* seed 16807) 0) 2147483647)) (/ seed 2147483647))
  (fcollect [_ 1 n] [(+ -24 (* 48 (rnd))) (+ -24 (* 48 (rnd))) (+ -2 (* 14 (rnd)))]))

(fn ray-toward [[ox oy oz] [tx ty tz] draw]
  ;; The ray from a point (raised to at least 0.01 above the floor) toward another:
  ;; its origin, its unit direction, and where it meets the floor (else `draw`).
  (let [oz (math.max oz 0.01)
        (a b c) (values (- tx ox) (- ty oy) (- tz oz))
        len (math.sqrt (+ (* a a) (* b b) (* c c)))
        (dx dy dz) (values (/ a len) (/ b len) (/ c len))]
    (values ox oy oz dx dy dz (if (< dz 0) (/ (- oz) dz) draw))))

(fn walks-as-brute-force [s]
  ;; Rays from around and inside the region in many directions: the walk (the
  ;; reference's march, as the shader's) against the closed-form entry into every
  ;; object and the floor. Returns the plan.
  (let [p (assert (plan.scene->plan s))
        T (reference.tracer s p {:cam-pos [0 -35 12]})
        draw s.render.draw-distance
        origins (points 300)
        targets (points 300 11)]
    (var hits 0)
    (each [i origin (ipairs origins)]
      ;; Toward another point of the region: most rays cross it.
      (let [(ox oy oz dx dy dz plane) (ray-toward origin (. targets i) draw)
            expected (math.min (field.brute-entry p.field ox oy oz dx dy dz draw) plane draw)
            t (T.march ox oy oz dx dy dz)]
        (when (< expected plane) (set hits (+ hits 1)))
        (assert.is_true (< (math.abs (- t expected)) 1e-9)
                        (string.format "ray %d: walked to %.12g, the first object is at %.12g" i t expected))))
    (assert.is_true (> hits 30) (.. hits " rays meet an object"))
    p))

(describe "fields"
  (fn []
    (it "take the spheres and boxes of a scene with at least min-objects of them"
      (fn []
        (let [few (scattered (- field.min-objects 1))
              many (scattered field.min-objects)]
          (assert.is_nil (field.members few.objects))
          (assert.is_nil (. (assert (plan.scene->plan few)) :field))
          (let [p (assert (plan.scene->plan many))]
            (assert.are.equal field.min-objects p.field.count)
            (assert.is_truthy (p.key:find "field" 1 true))
            ;; The field is the tape's first object (a strategy: lower.fnl), its
            ;; members numbered first; the floor is written out after it.
            (assert.are.same [:field :plane]
                             (icollect [_ o (ipairs p.tape.objects)]
                               (if o.field :field (. o.info.children 1 :kind))))
            (assert.are.equal field.min-objects (. p.tape.objects 1 :field :count))
            (assert.are.equal (+ 1 field.min-objects) p.tape.count)
            ;; plan.objects: the field's, in scene order, then the others.
            (assert.are.equal (. many.objects 2) (. p.objects 1))
            (assert.are.equal (. many.objects 3) (. p.objects 2))
            (assert.are.equal (. many.objects 1) (. p.objects (+ 1 field.min-objects)))))
        ;; Trees and planet-sized spheres stay out of a field.
        (assert.is_false (field.member? {:kind :sphere :pos [0 0 0] :radius 5000}))
        ;; A giant box (a floor made of a box) stays in the uniform arrays: in the
        ;; field it would stretch the grid over a million units.
        (assert.is_false (field.member? {:kind :box :pos [0 0 0] :size [1e6 1e6 1]}))
        (assert.is_true (field.member? {:kind :box :pos [0 0 0] :size [999 1 1]}))
        (let [s (scattered 100 "{:kind :box :pos [0 0 -0.5] :size [1e6 1e6 1] :color [0.5 0.5 0.5]}")
              p (assert (plan.scene->plan s))]
          (assert.are.equal 100 p.field.count)
          (assert.is_true (< (. p.field.size 1) 100)))
        (assert.is_false (field.member? {:kind :sphere :tree {} :pos [0 0 0] :radius 1}))
        (assert.is_false (field.member? {:kind :plane :height 0}))))

    (it "are left out when asked, without bounds, or beside an object that has no bound"
      (fn []
        (let [s (scattered 100)]
          (assert.is_nil (. (assert (plan.scene->plan s {:field? false :uniform-limit 1e6})) :field))
          (assert.is_nil (. (assert (plan.scene->plan s {:bounds? false :uniform-limit 1e6})) :field)))
        ;; An endless repetition has no bound: the plan falls back to uniform arrays.
        (let [s (scattered 100 "{:kind :repeat :period [4 4 0] :children [{:kind :sphere :radius 0.5}] :pos [0 0 30]}")
              p (assert (plan.scene->plan s))]
          (assert.is_nil p.field)
          (assert.is_nil p.bounds))))

    (it "list every object in every cell its box meets"
      (fn []
        (let [s (scattered 300)
              fd (. (assert (plan.scene->plan s)) :field)
              [lx ly lz] fd.lo]
          (var checked 0)
          (each [i [cx cy cz ax ay az r] (ipairs (shapes-of fd))]
            ;; The box's corners and centre, field-local.
            (each [_ [sx sy sz] (ipairs [[0 0 0] [-1 -1 -1] [1 1 1] [-1 1 -1] [1 -1 1]])]
              (let [(_ _ _ k) (field.cell-of fd (+ cx (* sx (+ ax r))) (+ cy (* sy (+ ay r)))
                                             (+ cz (* sz (+ az r))))
                    start (. fd.cell-start k)
                    listed? (accumulate [found? false j (ipairs fd.records) &until found?]
                              (and (> j start) (<= j (+ start (. fd.cell-count k)))
                                   (= i (. fd.records j))))]
                (set checked (+ checked 1))
                (assert.is_true listed? (.. "object " i " is not listed in cell " k)))))
          (assert.are.equal (* 5 300) checked))))

    (it "give the exact distance within reach and a lower bound beyond (brute force the oracle)"
      (fn []
        (let [fd (. (assert (plan.scene->plan (scattered 500))) :field)]
          (var near 0)
          (each [_ [x y z] (ipairs (points 3000))]
            (let [(d best) (field.distance fd x y z)
                  (exact nearest) (field.brute-distance fd x y z)]
              (assert.is_true (<= d (+ exact 1e-9))
                              (string.format "(%g %g %g): %g above the exact %g" x y z d exact))
              (when (<= exact fd.reach)
                (set near (+ near 1))
                (assert.is_true (< (math.abs (- d exact)) 1e-9))
                (assert.are.equal nearest best))))
          ;; The sample reaches objects, not only empty space.
          (assert.is_true (> near 20) (.. near " points within reach")))))

    (it "skip one object when asked, as mapOthers does"
      (fn []
        (let [fd (. (assert (plan.scene->plan (scattered 200))) :field)
              (cx cy cz) (field.shape-at fd 5)
              [lx ly lz] fd.lo
              (x y z) (values (+ lx cx) (+ ly cy) (+ lz cz))]
          (assert.are.equal 5 (select 2 (field.distance fd x y z)))
          (assert.are_not.equal 5 (select 2 (field.distance fd x y z 5)))
          (assert.is_true (> (field.distance fd x y z 5) (field.distance fd x y z))))))

    (it "refuse a grid whose lists would not fit in a texture, saying what to remove"
      (fn []
        ;; 3000 boxes on top of each other: each is listed in every one of the grid's
        ;; 6000-odd cells, about 18 million records for a texture of 8.4 million.
        (let [s (assert (scene.load-string
                         "{:objects (fcollect [i 1 3000] {:kind :box :pos [(* i 0.001) 0 0] :size [100 100 100]})}"
                         "big.fnl"))
              (p err) (plan.scene->plan s)]
          (assert.is_nil p)
          (assert.is_truthy (err:find "^big%.fnl: objects: the field's grid lists its 3000 spheres and boxes %d+ times"))
          (assert.is_truthy (err:find "more than the 8388608 a texture holds; remove or shrink the largest ones" 1 true)))))

    (it "pack their textures: cells, records with 0-based object numbers, objects"
      (fn []
        (let [fd (. (assert (plan.scene->plan (scattered 100))) :field)
              tex (field.textures fd)]
          (assert.are.equal tex (field.textures fd))   ; made once
          (each [_ t (ipairs [tex.cells tex.records tex.objects])]
            (assert.are.equal field.texture-width t.width)
            (assert.is_true (<= t.count (* 4 t.width t.height))))
          (assert.are.equal (* 4 (length fd.cell-start)) tex.cells.count)
          (assert.are.equal (* 8 (length fd.records)) tex.records.count)
          (assert.are.equal (* 12 fd.count) tex.objects.count)
          ;; Float32, as the GPU reads them; past :count, zeros to the texture's end.
          (let [records (field.texture-values tex.records)
                objects (field.texture-values tex.objects)]
            ;; Record 1 is object (. fd.records 1), stored 0-based.
            (assert.are.equal (- (. fd.records 1) 1) (. records 8))
            ;; Object 2 is a box: no radius, half extents; its colour.
            (let [o (. fd.objects 2)]
              (assert.are.equal :box o.kind)
              (assert.are.equal 0 (. objects (+ 12 4)))
              (assert.are.equal (f32 (* 0.5 (. o.size 2))) (. objects (+ 12 6)))
              (assert.are.same (icollect [_ c (ipairs o.color)] (f32 c))
                               [(. objects (+ 12 9)) (. objects (+ 12 10)) (. objects (+ 12 11))])))
          (let [last (* 4 tex.objects.width tex.objects.height)]
            (assert.are.equal 0 (. tex.objects.floats (- last 1)))))))

    (it "give a field of spheres a walk texture: a cell's one sphere, where its list starts, or its clearances"
      (fn []
        (let [fd (. (assert (plan.scene->plan (scattered 400 nil nil true))) :field)
              walk fd.walk
              cells (length walk.start)
              data (field.texture-values (. (field.textures fd) :walk))
              texel (fn [i] [(. data (+ (* 4 i) 1)) (. data (+ (* 4 i) 2))
                             (. data (+ (* 4 i) 3)) (. data (+ (* 4 i) 4))])
              ;; float32 in the texture, as the shader reads it.
              sphere (fn [i] (let [(cx cy cz _ _ _ r) (field.shape-at fd i)] [(f32 cx) (f32 cy) (f32 cz) (f32 r)]))
              seen {:empty 0 :one 0 :several 0}]
          (assert.is_true fd.walk?)
          (assert.is_true (>= fd.turns fd.crossings))
          (var at cells)
          (for [k 1 cells]
            (let [first (. walk.start k)
                  n (. walk.count k)]
              (case n
                ;; (clearances of at least 1 in each octant: see the next test)
                0 (let [[a b c w] (texel (- k 1))]
                    (tset seen :empty (+ seen.empty 1))
                    (assert.is_true (and (>= a 65793) (>= b 65793) (>= c 257)))
                    (assert.are.equal 0 w))
                1 (do (tset seen :one (+ seen.one 1))
                      (assert.are.same (sphere (. walk.records (+ first 1))) (texel (- k 1))))
                ;; A list of several: the sphere about them (radius negated), then
                ;; each, the lists one after another in their cells' order.
                _ (let [[bx by bz br] (texel at)]
                    (tset seen :several (+ seen.several 1))
                    (assert.are.same [at (+ n 1) 0 -1] (texel (- k 1)))
                    (assert.is_true (< br 0))
                    (for [j 1 n]
                      (let [[cx cy cz r &as s] (sphere (. walk.records (+ first j)))]
                        (assert.are.same s (texel (+ at j)))
                        (assert.is_true (<= (+ r (math.sqrt (+ (^ (- cx bx) 2) (^ (- cy by) 2) (^ (- cz bz) 2))))
                                            (- br)))))
                    (set at (+ at n 1))))))
          (assert.are.equal (* 4 at) (length data))
          (assert.is_true (and (> seen.empty 0) (> seen.one 0) (> seen.several 0)))
          ;; Its lists are the field's, but grown by less: never longer, and every
          ;; sphere still in each cell its box meets.
          (for [k 1 cells]
            (assert.is_true (<= (. walk.count k) (. fd.cell-count k))))
          (each [i [cx cy cz _ _ _ r] (ipairs (shapes-of fd))]
            (each [_ [sx sy sz] (ipairs [[0 0 0] [-1 -1 -1] [1 1 1] [-1 1 -1] [1 -1 1]])]
              (let [(_ _ _ k) (field.cell-of fd (+ cx (* sx r)) (+ cy (* sy r)) (+ cz (* sz r)))
                    first (. walk.start k)]
                (assert.is_true (accumulate [found? false j (ipairs walk.records) &until found?]
                                  (and (> j first) (<= j (+ first (. walk.count k)))
                                       (= i (. walk.records j))))
                                (.. "sphere " i " is not in the walk's list of cell " k))))))))

    (it "walk a field with boxes through the field's lists, with no walk texture"
      (fn []
        (let [fd (. (assert (plan.scene->plan (scattered 100))) :field)]
          (assert.is_nil fd.walk?)
          (assert.is_nil (. (field.textures fd) :walk)))))

    (it "find the texels a value edit changed, so only those are uploaded"
      (fn []
        (let [s (scattered 100)
              before (field.textures (. (assert (plan.scene->plan s)) :field))]
          ;; One box's colour: one texel of the objects texture (object 2's third). A
          ;; value edit loads the scene again: a new list of objects.
          (let [edited (doto (collect [k v (pairs s)] k v)
                         (tset :objects (icollect [i o (ipairs s.objects)]
                                          (if (= i 3) (doto (collect [k v (pairs o)] k v) (tset :color [0.1 0.2 0.3]))
                                              o))))
                after (field.textures (. (assert (plan.scene->plan edited)) :field))]
            (assert.are.same [[0 5 5]] (field.changed-spans before.objects after.objects))
            (assert.are.same [] (field.changed-spans before.cells after.cells))
            (assert.are.same [] (field.changed-spans before.records after.records))))
        ;; Two rows of 2 texels: a change in each row gives one span per row; lengths
        ;; that differ mean a new texture.
        (let [a {:width 2 :data (fcollect [_ 1 16] 0)}
              b {:width 2 :data (fcollect [i 1 16] (if (or (= i 2) (= i 13) (= i 16)) 1 0))}]
          (assert.are.same [[0 0 0] [1 1 1]] (field.changed-spans a b))
          (assert.is_nil (field.changed-spans a {:width 2 :data [0 0 0 0]})))))

    (it "are built once for the plans of one scene, but for one whose values change in place"
      (fn []
        (let [s (scattered 100)
              a (assert (plan.scene->plan s))
              b (assert (plan.scene->plan s {:fold? true}))]
          ;; The player's plan, its folded twin: one field, one set of textures.
          (assert.are.equal a.field b.field)
          ;; Other options, another field.
          (assert.are_not.equal a.field (. (assert (plan.scene->plan s {:field-cells 8})) :field))
          ;; Functions of time set their values in the scene itself each frame.
          (set s.animated [{:path [:objects 3 :color]}])
          (let [c (assert (plan.scene->plan s))]
            (tset (. s.objects 3) :color [0.1 0.2 0.3])
            (let [d (assert (plan.scene->plan s))]
              (assert.are_not.equal c.field d.field)
              (assert.are.same [[0 5 5]] (field.changed-spans (. (field.textures c.field) :objects)
                                                              (. (field.textures d.field) :objects))))))))

    (it "send the grid's corner camera-relative and its textures as texture uniforms"
      (fn []
        (let [s (scattered 100)
              p (assert (plan.scene->plan s))
              cam (camera.from-scene s)
              us (collect [_ u (ipairs (uniforms.pack s p cam 64 36))] u.name u)
              [lx ly lz] p.field.lo
              [cx cy cz] cam.pos]
          (assert.are.same [(- lx cx) (- ly cy) (- lz cz)] (. us :uFieldOrigin :values))
          (assert.are.equal :texture (. us :uFieldRecords :type))
          (assert.are.equal (. (field.textures p.field) :cells) (. us :uFieldCells :texture))
          (assert.are.same [p.field.crossings] (. us :uFieldCrossings :values)))))

    (it "generate the grid march and the field's terms, and no Shadertoy export"
      (fn []
        (let [s (scattered 100)
              p (assert (plan.scene->plan s))
              text (assert (codegen.shader p :core))]
          (assert.is_truthy (text:find "float fieldMap(vec3 p, int skip, out int best)" 1 true))
          (assert.is_truthy (text:find "fieldNextCell(tNext, index, tDelta, stride);" 1 true))
          ;; Nothing but the field and the floor: the lean walk.
          (assert.is_truthy (text:find "nothing is sphere-traced" 1 true))
          ;; Every object's normal in closed form: the plane's, the field's.
          (assert.is_truthy (text:find "if (gObject >= 0 && gObject < 100) n = fieldNormal(p, gObject);" 1 true))
          (assert.is_truthy (text:find "if (gObject == 100) {  // objects[1]: plane" 1 true))
          (assert.is_truthy (text:find "n = gradGround(p, " 1 true))
          (assert.is_nil (text:find "mapObject" 1 true))
          (assert.is_truthy (text:find "#define fieldOthers() false" 1 true))
          (let [(out err) (export.shadertoy s p)]
            (assert.is_nil out)
            (assert.is_truthy (err:find "100 spheres and boxes in float textures" 1 true))))))

    (it "walk the grid to the first object a ray meets, as brute force over every object finds it"
      (fn []
        ;; Spheres and boxes: the lean walk, the field's lists.
        (let [p (walks-as-brute-force (scattered 600))]
          (assert.is_nil p.field.walk))))

    (it "walk a field of spheres through lists of its own, as brute force finds the first sphere"
      (fn []
        ;; Spheres alone: march.glsl's step-spheres and its lists (the reference walks
        ;; them too). 2000 spheres of radius 0.2 to 0.7 leave many cells listing
        ;; several, so the list turns are walked.
        (let [p (walks-as-brute-force (scattered 2000 nil nil true))
              several (accumulate [n 0 _ c (ipairs p.field.walk.count)] (if (> c 1) (+ n 1) n))]
          (assert.is_true p.field.walk?)
          (assert.is_true (> several 500) (.. several " cells list several spheres"))
          ;; The shader walks it, sent as a texture with its bound on turns.
          (assert.is_truthy (: (codegen.shader p :core) :find "uniform sampler2D uFieldWalk;" 1 true))
          (let [s (scattered 2000 nil nil true)
                us (collect [_ u (ipairs (uniforms.pack s p (camera.from-scene s) 160 90))] u.name u)]
            (assert.are.equal (. (field.textures p.field) :walk) (. us :uFieldWalk :texture))
            (assert.are.same [p.field.turns] (. us :uFieldTurns :values))))))

    (it "give each empty cell of a walk its clearances: the largest empty cubes on from it"
      (fn []
        ;; walk-texture: an empty cell's texel holds, for each octant of ray
        ;; directions (o = (x < 0) + 2 (y < 0) + 4 (z < 0); 8 bits each, three to a
        ;; float) and 0 (w), its clearance k: the cube of k cells along each axis
        ;; from the cell on in the octant's directions is empty (past the grid
        ;; counts as empty), and the cube of k + 1 is not (or k is 255). Checked by
        ;; brute force over a fine grid, where clearances of several cells occur.
        (let [s (scattered 300 nil nil true)
              fd (assert (field.build (field.members s.objects) {:cells-per-object 40}))
              [nx ny nz] fd.dims
              data (field.texture-values (. (field.textures fd) :walk))
              occupied? (fn [x y z]
                          (and (>= x 0) (< x nx) (>= y 0) (< y ny) (>= z 0) (< z nz)
                               (> (. fd.walk.count (+ 1 x (* nx (+ y (* ny z))))) 0)))
              ;; Whether the cube of n cells from (x y z) on along (sx sy sz) is empty
              ;; (its cells in the grid).
              last (fn [q s n dim] (if (> s 0) (math.min (- n 1) (- dim 1 q)) (math.min (- n 1) q)))
              empty-cube? (fn [x y z sx sy sz n]
                            (var empty? true)
                            (for [c 0 (last z sz n nz) &until (not empty?)]
                              (for [b 0 (last y sy n ny) &until (not empty?)]
                                (for [a 0 (last x sx n nx) &until (not empty?)]
                                  (when (occupied? (+ x (* sx a)) (+ y (* sy b)) (+ z (* sz c)))
                                    (set empty? false)))))
                            empty?)]
          (var wide 0)
          (var checked 0)
          (for [k 1 (* nx ny nz) 13]
            (when (= 0 (. fd.walk.count k))
              (let [i (- k 1)
                    x (% i nx) y (% (math.floor (/ i nx)) ny) z (math.floor (/ i (* nx ny)))
                    at (* 4 i)]
                (assert.are.equal 0 (. data (+ at 4)))
                (for [o 0 7]
                  (let [sx (if (= 0 (% o 2)) 1 -1)
                        sy (if (= 0 (% (math.floor (/ o 2)) 2)) 1 -1)
                        sz (if (< o 4) 1 -1)
                        packed (. data (+ at 1 (math.floor (/ o 3))))
                        clearance (% (math.floor (/ packed (^ 256 (% o 3)))) 256)]
                    (set checked (+ checked 1))
                    (assert.is_true (>= clearance 1))
                    (assert.is_true (empty-cube? x y z sx sy sz clearance)
                                    (string.format "cell %d %d %d, octant %d: %d" x y z o clearance))
                    (assert.is_true (or (= clearance 255) (not (empty-cube? x y z sx sy sz (+ clearance 1))))
                                    (string.format "cell %d %d %d, octant %d: more than %d" x y z o clearance))
                    (when (>= clearance 3) (set wide (+ wide 1))))))))
          (assert.is_true (> checked 1000) (.. checked " clearances checked"))
          (assert.is_true (> wide 100) (.. wide " clearances of 3 or more")))))

    (it "walk a field of spheres as the shader does, jumping across empty cells, to the first sphere"
      (fn []
        ;; field.walk, march.glsl's step-spheres on the CPU (the walk texture as the
        ;; shader reads it): the ray's first sphere as brute force finds it, at the
        ;; benchmark's grid and at finer ones whose empty cells have wide clearances
        ;; (the walk jumps across several cells at once).
        (let [s (scattered 2000 nil nil true)
              members (field.members s.objects)
              draw s.render.draw-distance
              origins (points 300)
              targets (points 300 11)]
          (each [_ per-object (ipairs [2 16 64])]
            (let [fd (assert (field.build members {:cells-per-object per-object}))
                  ;; The walk reads its spheres as float32, as the shader does: brute
                  ;; force over the same spheres rounded so (a grazing ray's entry
                  ;; moves by far more than the rounding: 1.3e-5 at 17.8 units).
                  rounded (doto (collect [k v (pairs fd)] k v)
                            (tset :shapes (let [n (* 7 fd.count)
                                                a (ffi.new "double[?]" n)]
                                            (for [j 0 (- n 1)] (tset a j (f32 (. fd.shapes j))))
                                            a)))]
              (assert.is_true fd.walk?)
              (var hits 0)
              (each [i origin (ipairs origins)]
                (let [(ox oy oz dx dy dz plane) (ray-toward origin (. targets i) draw)
                      t-past (math.min plane draw)
                      expected (math.min (field.brute-entry rounded ox oy oz dx dy dz draw) t-past)
                      t (field.walk fd ox oy oz dx dy dz t-past 1e9)]
                  (when (< expected t-past) (set hits (+ hits 1)))
                  (assert.is_true (< (math.abs (- t expected)) 1e-9)
                                  (string.format "%d cells an object, ray %d: walked to %s, the first sphere is at %.12g"
                                                 per-object i (tostring t) expected))))
              (assert.is_true (> hits 30) (.. hits " rays meet a sphere"))))
          ;; Out of steps: where the walk stopped, after max-steps cells that list
          ;; something.
          (let [fd (assert (field.build members))
                (t steps stop) (field.walk fd -25 0 5 1 0 0 draw 1)]
            (assert.are.equal :out t)
            (assert.are.equal 1 steps)
            (assert.is_true (> stop 0))))))

    (it "walk beside other objects as brute force marches them"
      (fn []
        ;; A torus (a tree: in a union, not a marched member) and the floor beside 300
        ;; field objects: the general walk sphere-traces the torus alongside the cells
        ;; (the bug this caught: a tree beside the field was never tested for a hit,
        ;; so mirror rays went through it). Measured: the same objects along 296 of
        ;; 300 paths; with that bug 289.
        (let [s (scattered 300 "{:kind :union :pos [0 0 4] :color [0.9 0.6 0.2] :children [{:kind :torus :radius 3 :thickness 0.8}]}")
              (pf a b) (against-brute-force s 300)
              same (accumulate [n 0 i ra (ipairs a)]
                     (if (= (table.concat ra.path ",") (table.concat (. b i :path) ",")) (+ n 1) n))]
          (assert.are.equal 1 pf.bounds.count)
          ;; Every bounce hits the same objects but at the threshold's band.
          (assert.is_true (>= same 294) (.. same " of 300 pixels see the same objects")))))

    (it "show what marching every object shows, but for the hit threshold's band"
      (fn []
        ;; The field meets its objects exactly; the march counts a ray passing within
        ;; the hit threshold (epsilon times the distance) as a hit, so silhouettes and
        ;; shadow edges move by that much. Measured at 160x90 on 400 pixels: the same
        ;; object under 398, colours within 2/255 at 383 (the CPU in double: the same
        ;; figures every run).
        (let [(pf a b) (against-brute-force (scattered 600) 400)
              same (accumulate [n 0 i ra (ipairs a)] (if (= ra.object (. b i :object)) (+ n 1) n))
              close (accumulate [n 0 i ra (ipairs a)]
                      (if (<= (compare.pixel-diff (icollect [_ c (ipairs ra.color)] (* 255 c))
                                                  (icollect [_ c (ipairs (. b i :color))] (* 255 c)))
                              2)
                          (+ n 1) n))]
          (assert.is_truthy pf.field)
          (assert.is_true (>= same 396) (.. same " of 400 pixels show the same object"))
          (assert.is_true (>= close 380) (.. close " of 400 pixels within 2/255")))))))

(fn scattered-mixed [n]
  ;; n spheres, rotated tori and capsules, the tori and capsules marched members.
  (assert (scene.load-string (marched-mix n) "t.fnl")))

(fn first-object [text]
  (. (assert (scene.load-string (.. "{:objects [" text "]}") "t.fnl")) :objects 1))

(describe "a field's marched members"
  (fn []
    (it "are any bounded primitive placed by :pos and :rotate and coloured alone"
      (fn []
        (each [_ text (ipairs ["{:kind :torus :pos [1 2 3] :rotate [10 20 30] :color [1 0 0]}"
                               "{:kind :capsule :a [0 0 0] :b [1 0 0] :radius 0.2}"
                               "{:kind :octahedron :size 0.5 :pos [0 0 1]}"])]
          (assert.is_true (field.member? (first-object text)) text))
        ;; A material of its own, a scale, a tree around it, an unbounded primitive,
        ;; a planet's size: not a member.
        (each [_ text (ipairs ["{:kind :torus :pos [1 2 3] :mirror 0.5}"
                               "{:kind :torus :pos [1 2 3] :scale 2}"
                               "{:kind :union :children [{:kind :torus}]}"
                               "{:kind :cylinder :radius 1}"
                               "{:kind :torus :radius 5000 :thickness 1}"])]
          (assert.is_false (field.member? (first-object text)) text))
        (let [p (assert (plan.scene->plan (scattered-mixed 60)))
              text (assert (codegen.shader p :core))]
          (assert.are.equal 60 p.field.count)
          (assert.are.same [:torus :capsule] p.field.kinds.marched)
          (assert.is_truthy (p.key:find "field:60s,torus,capsule" 1 true))
          ;; Each kind's distance from its own descriptor, its numbers read from
          ;; the objects texture; no exact normal for the field (differences).
          (assert.is_truthy (text:find "if (kind == 1) {\n        return sdTorus(l, u.x, u.y);\n    }" 1 true))
          (assert.is_truthy (text:find "return sdCapsule(l, u.xyz, vec3(u.w, v.x, v.y), v.z);" 1 true))
          (assert.is_falsy (text:find "fieldNormal(p, gObject)" 1 true))
          ;; The Lua emitter: a member's distance is its primitive's in its frame.
          (let [emit-lua (require :src.sdf.emit-lua)
                tape (emit-lua.compile p.tape)
                torus (. p.objects 1)
                [x y z] torus.tree.pos
                R torus.tree.radius
                at (fn [px py pz] ((. tape.distance 1) px py pz))]
            (assert.are.equal :torus torus.kind)
            ;; At its centre the ring is R away, less the tube; the rotation keeps it.
            (assert.is_true (< (math.abs (- (at x y z) (- R torus.tree.thickness))) 1e-12))
            (assert.is_false (. tape.gradient 1))))))

    (it "see a primitive placed by explicit operations as its shorthands place it"
      (fn []
        ;; Translations and rotations written as operations of one child, in either
        ;; order and with the shorthands inside: the field's evaluator (the chain's
        ;; rows and origin, lower.fnl's field-marched) against the tree lowered as
        ;; usual (no field), at 200 points.
        (let [shapes ["{:kind :translate :offset [1 2 3] :children [{:kind :rotate :angles [10 40 70] :children [{:kind :torus :radius 0.6 :thickness 0.2}]}]}"
                      "{:kind :rotate :axis [0.6 0 0.8] :angle 33 :children [{:kind :translate :offset [-2 1 0.5] :children [{:kind :capsule :a [0 0 0] :b [0.5 0.2 0] :radius 0.2 :pos [0.3 0 0] :rotate [0 20 0]}]}]}"
                      "{:kind :rotate :angles [0 0 90] :pos [4 4 1] :color [1 0 0] :children [{:kind :octahedron :size 0.5 :rotate [30 0 0]}]}"]
              text (table.concat (fcollect [i 1 18] (. shapes (+ 1 (% i 3)))) " ")
              s (assert (scene.load-string (.. "{:objects [" text "]}") "t.fnl"))
              emit-lua (require :src.sdf.emit-lua)
              pf (assert (plan.scene->plan s))
              pt (assert (plan.scene->plan s {:field? false}))
              df (. (emit-lua.compile pf.tape) :distance)
              dt (. (emit-lua.compile pt.tape) :distance)
              pts (points 200)]
          (assert.are.equal 18 pf.field.count)
          (assert.is_nil pt.field)
          (assert.is_true (field.member? (. s.objects 1)))
          (assert.is_false (field.member? (first-object "{:kind :translate :children [{:kind :union :children [{:kind :torus}]}]}")))
          (assert.is_false (field.member? (first-object "{:kind :rotate :children [{:kind :torus :mirror 0.5}]}")))
          (for [i 1 3]
            ;; (the field numbers its members in scene order, as the tape does here)
            (assert.are.equal (. pf.objects i) (. pt.objects i))
            (each [_ [x y z] (ipairs pts)]
              (let [a ((. df i) x y z) b ((. dt i) x y z)]
                (assert.is_true (< (math.abs (- a b)) 1e-9)
                                (string.format "object %d at %g %g %g: field %.12g, tree %.12g" i x y z a b))))))))

    (it "hold every bounded primitive, each drawn as the tree it would be"
      (fn []
        ;; Every primitive with a box, of Lipschitz factor 1 and no variant: 16
        ;; rotated copies of each (its defaults) form a field; each member's
        ;; evaluator (its descriptor's CPU form in its frame) against the same
        ;; object lowered as a tree (no field), at 60 points around it. The others
        ;; (a plane, a cylinder: unbounded) stay out.
        (let [primitives (require :src.sdf.primitives)
              emit-lua (require :src.sdf.emit-lua)
              marched []
              left-out []]
          (each [_ desc (ipairs primitives.all)]
            (let [text (table.concat
                        (fcollect [i 1 16]
                          (string.format "{:kind :%s :pos [%d %d 1] :rotate [%d %d %d] :color [0.5 0.5 0.5]}"
                                         desc.kind (* 3 (% i 4)) (* 3 (math.floor (/ i 4)))
                                         (* 17 i) (* 29 i) (* 41 i)))
                        " ")
                  s (assert (scene.load-string (.. "{:objects [" text "]}") "t.fnl"))]
              (if (not (field.member? (. s.objects 1)))
                  (table.insert left-out desc.kind)
                  (let [pf (assert (plan.scene->plan s))
                        pt (assert (plan.scene->plan s {:field? false :grids? false :uniform-limit 1e6}))
                        df (. (emit-lua.compile pf.tape) :distance)
                        dt (. (emit-lua.compile pt.tape) :distance)]
                    (table.insert marched desc.kind)
                    (assert.are.same [desc.kind] pf.field.kinds.marched)
                    (each [_ i (ipairs [1 7 16])]
                      (let [[x y z] (. s.objects i :tree :pos)]
                        (for [j 1 60]
                          (let [px (+ x (* 2 (math.sin (* 1.3 j)))) py (+ y (* 2 (math.cos (* 2.1 j))))
                                pz (+ z (* 1.5 (math.sin (* 0.7 j))))
                                a ((. df i) px py pz) b ((. dt i) px py pz)]
                            ;; (A bound, :bound, is lowered with its box's far field,
                            ;; max(d, box): the same where it is under the box's
                            ;; distance, a larger bound beyond.)
                            (assert.is_true (if (= desc.class :exact) (< (math.abs (- a b)) 1e-9)
                                                (or (< (math.abs (- a b)) 1e-9) (< a b)))
                                            (string.format "%s %d: field %.12g, tree %.12g"
                                                           desc.kind i a b))))))))))
          (table.sort left-out)
          (assert.are.same [:cylinder :plane] left-out)
          (assert.is_true (>= (length marched) 26) (table.concat marched " ")))))

    (it "carry their rotation as a quaternion that turns a vector as its rows do"
      (fn []
        ;; field-primitives.glsl's fieldTurn (v + 2 q x (q x v + w v)) with
        ;; field.quaternion's q, against the rows, for rotations that reach each of
        ;; its four branches (the trace, then the largest diagonal term).
        (let [rows (. (require :src.sdf.operations) :lookup)
              rotate (. (rows :rotate) :pack)
              cross (fn [ax ay az bx by bz]
                      (values (- (* ay bz) (* az by)) (- (* az bx) (* ax bz)) (- (* ax by) (* ay bx))))
              turn (fn [qx qy qz qw x y z]
                     (let [(cx cy cz) (cross qx qy qz x y z)
                           (ex ey ez) (cross qx qy qz (+ cx (* qw x)) (+ cy (* qw y)) (+ cz (* qw z)))]
                       (values (+ x (* 2 ex)) (+ y (* 2 ey)) (+ z (* 2 ez)))))]
          (each [_ o (ipairs [{:angles [10 40 70] :angle 0} {:angles [180 0 0] :angle 0}
                              {:angles [0 180 0] :angle 0} {:angles [0 0 180] :angle 0}
                              {:angles [170 10 175] :angle 0} {:axis [0.6 0 0.8] :angle 179}
                              {:axis [0 1 0] :angle -91} {:angles [0 0 0] :angle 0}])]
            (let [[a b c d e f g h k] (rotate o)
                  (qx qy qz qw) (field.quaternion [a b c d e f g h k])]
              (assert.is_true (< (math.abs (- 1 (+ (* qx qx) (* qy qy) (* qz qz) (* qw qw)))) 1e-12))
              (each [_ [x y z] (ipairs [[1 0 0] [0 1 0] [0 0 1] [0.3 -2 1.7]])]
                (let [(tx ty tz) (turn qx qy qz qw x y z)]
                  (assert.is_true (< (math.max (math.abs (- tx (+ (* a x) (* b y) (* c z))))
                                               (math.abs (- ty (+ (* d x) (* e y) (* f z))))
                                               (math.abs (- tz (+ (* g x) (* h y) (* k z)))))
                                     1e-12)
                                  (.. "rotation " (table.concat (or o.angles o.axis) " "))))))))))

    (it "are met where a fine search along the ray first finds the surface"
      (fn []
        ;; The oracle: the member's distance sampled every thousandth of its bounding
        ;; sphere's diameter along the ray, the surface's bracket the first sample
        ;; inside (distance <= 0). The march must stop no later than that, where the
        ;; distance is under the hit threshold (which a grazing ray meets well before
        ;; the surface along it); a ray whose samples all stay farther than the
        ;; threshold must miss. Rays aim at random points near each member, from 10
        ;; to 40 units away: 720 rays, 428 hits, 247 misses, 45 grazing (either).
        (let [p (assert (plan.scene->plan (scattered-mixed 90)))
              fd p.field
              eps 0.001
              hit {:t0 0 :threshold (fn [d] (* eps d)) :start-limit (fn [d] (* 0.5 d))}
              unit (fn [a b c] (let [l (math.sqrt (+ (* a a) (* b b) (* c c)))] (values (/ a l) (/ b l) (/ c l))))]
          (var seed 9)
          (fn rnd [] (set seed (% (* seed 16807) 2147483647)) (/ seed 2147483647))
          (var (hits misses grazing) (values 0 0 0))
          (for [i 1 fd.count]
            (when (. fd.marched i)
              (for [_ 1 12]
                (let [(cx cy cz _ _ _ r) (field.shape-at fd i)
                      (ux uy uz) (unit (- (rnd) 0.5) (- (rnd) 0.5) (- (rnd) 0.5))
                      far (+ 10 (* 30 (rnd)))
                      ;; from far away toward a point within the bounding sphere
                      (tx ty tz) (values (+ cx (* r 0.8 (- (rnd) 0.5))) (+ cy (* r 0.8 (- (rnd) 0.5)))
                                         (+ cz (* r 0.8 (- (rnd) 0.5))))
                      (qx qy qz) (values (+ tx (* far ux)) (+ ty (* far uy)) (+ tz (* far uz)))
                      (dx dy dz) (values (- ux) (- uy) (- uz))
                      t (field.marched-entry fd i qx qy qz dx dy dz math.huge hit)
                      at (fn [s] (field.member-distance fd i (+ qx (* dx s)) (+ qy (* dy s)) (+ qz (* dz s))))
                      step (/ (* 2 r) 1000)]
                  (var (s inside near) (values (- far (* 1.2 r)) nil math.huge))
                  (while (and (not inside) (< s (+ far (* 1.2 r))))
                    (let [d (at s)]
                      (set near (math.min near (- d (* eps s))))
                      (when (<= d 0) (set inside s)))
                    (set s (+ s step)))
                  (if inside
                      (do (set hits (+ hits 1))
                          (assert.is_true (and (<= t inside) (< (at t) (* eps t)))
                                          (string.format "member %d: marched to %s, the surface within (%.9g, %.9g]"
                                                         i (tostring t) (- inside step) inside)))
                      (> near 0)
                      (do (set misses (+ misses 1))
                          (assert.are.equal math.huge t (.. "member " i ": a miss marched to " t)))
                      (set grazing (+ grazing 1)))))))
          (assert.is_true (and (> hits 100) (> misses 50)) (.. hits " hits, " misses " misses, " grazing " grazing")))))

    (it "walk as marching every object shows, but for the hit threshold's band"
      (fn []
        ;; The reference's march through the field against the same scene with no
        ;; field (every object sphere-traced at every step). Measured at 160x90 on
        ;; 300 pixels: the same object under all 300 (at least 296 allowed: a ray
        ;; grazing a surface within the hit threshold may meet it at another step).
        (let [(pf a b) (against-brute-force (scattered-mixed 300) 300)
              same (accumulate [n 0 i ra (ipairs a)] (if (= ra.object (. b i :object)) (+ n 1) n))]
          (assert.are.equal 300 pf.field.count)
          (assert.is_true (>= same 296) (.. same " of 300 pixels show the same object")))))))

;; A large field without functions of time lets its textures' floats go once a
;; backend has its own copy (LÖVE keeps one and the driver another: 150 MB a third
;; time for 1,000,000 spheres); anything that reads them after gets them made again,
;; the same numbers in the same tables (a backend's images are keyed by them).
(describe "a field's textures let go after their upload"
  (fn []
    (fn copy-of [tex]
      (let [n (* 4 tex.width tex.height)
            out (ffi.new "float[?]" n)]
        (ffi.copy out tex.floats (* 4 n))
        (values out n)))

    (fn same? [a b n]
      (var same true)
      (for [i 0 (- n 1) &until (not same)]
        (when (not= (. a i) (. b i)) (set same false)))
      same)

    (it "go for 100,000 spheres without functions of time, and come back the same"
      (fn []
        (let [s (scattered 100000 nil nil true)
              p (assert (plan.scene->plan s))
              fd p.field
              tex (field.textures fd)
              kept (collect [k t (pairs tex)] k [(copy-of t)])]
          (assert.is_true fd.static?)
          (each [k t (pairs tex)]
            (assert.is_true t.release? k)
            (field.release-floats! t)
            (assert.is_nil t.floats k))
          ;; The same tables (uniforms made again name them), still without floats.
          (assert.are.equal tex (field.textures fd))
          (assert.is_nil tex.objects.floats)
          ;; The CPU walk reads them: made again, equal to the first.
          (let [[ox oy oz] [0 -35 5]
                t (field.walk fd ox oy oz 0 1 0 1000 100000)]
            (assert.is_true (< t 1000)))
          (each [k t (pairs tex)]
            (let [[old n] (. kept k)]
              (assert.is_true (not= nil t.floats) k)
              (assert.is_true (same? old t.floats n) k)))
          ;; A texture whose floats went has nothing to compare: a value edit
          ;; uploads it whole.
          (field.release-floats! tex.objects)
          (assert.is_nil (field.changed-spans tex.objects (. (field.textures fd) :objects))))))

    (it "stay for a small field, and for one with functions of time"
      (fn []
        (let [fd (. (assert (plan.scene->plan (scattered 2000))) :field)
              tex (field.textures fd)]
          (field.release-floats! tex.objects)
          (assert.is_true (not= nil tex.objects.floats)))
        (let [s (scattered 20 "{:kind :sphere :pos (fn [t] [0 0 (+ 1 t)]) :radius 0.5}")
              fd (. (assert (plan.scene->plan s)) :field)]
          (assert.is_false fd.static?))))))
