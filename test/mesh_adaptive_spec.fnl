;; tier: fast
;; Adaptive meshes (--adaptive, src/mesh/simplify.fnl): fewer triangles at the same
;; largest distance from the surface, still closed, 2-manifold and free of crossing
;; triangles, with the materials' borders kept. Pure: plain LuaJIT.

(local load (require :src.scene.load))
(local export (require :src.mesh.export))
(local contour (require :src.mesh.contour))
(local mesh-scene (require :src.mesh.scene))
(local check (require :src.mesh.check))
(local intersect (require :src.mesh.intersect))
(local simplify (require :src.mesh.simplify))

(fn cut-values [scene grid]
  "The values of `scene`'s field as the mesher cut it (the level set meshed is 0)."
  (let [field (assert (mesh-scene.cpu-field (. (assert (mesh-scene.select-objects scene)) :scene)))
        values-of (contour.cut-field field grid.cut {:points 0 :work 0} (fn []) grid.h)]
    (fn [flat] (values-of :check flat))))

(fn largest-distance [scene r]
  ;; Over the triangles, read a tenth of a cell apart (a quarter missed the
  ;; midpoints of some edges: machined-part at 64, 0.459 cells where there is 0.486).
  (check.triangles-distance r.mesh (cut-values scene r.grid) (* 0.1 r.grid.h)))

(fn sound! [m h label]
  "Closed, 2-manifold, oriented; no two triangles crossing, none folded over another
at a shared corner."
  (let [t (check.topology m)
        x (intersect.self-intersections m {:min-length (* 1e-6 h)})]
    (assert.is_true t.manifold? (.. label ": " (check.describe t)))
    (assert.are.equal 0 x.pairs (.. label ": crossing pairs"))
    (assert.are.equal 0 x.folds (.. label ": folds"))))

(fn vertex-keys [m]
  (let [keys {}]
    (for [i 1 (length m.positions) 3]
      (tset keys (string.format "%.17g %.17g %.17g" (. m.positions i) (. m.positions (+ i 1))
                                (. m.positions (+ i 2)))
            true))
    keys))

(fn icosphere [radius levels inward?]
  "A sphere of triangles: an icosahedron's faces split `levels` times, its vertices
pushed to `radius`; turned inside out if `inward?`."
  (let [t (/ (+ 1 (math.sqrt 5)) 2)
        points [[-1 t 0] [1 t 0] [-1 (- t) 0] [1 (- t) 0] [0 -1 t] [0 1 t] [0 -1 (- t)]
                [0 1 (- t)] [t 0 -1] [t 0 1] [(- t) 0 -1] [(- t) 0 1]]
        faces [[1 12 6] [1 6 2] [1 2 8] [1 8 11] [1 11 12] [2 6 10] [6 12 5] [12 11 3]
               [11 8 7] [8 2 9] [4 10 5] [4 5 3] [4 3 7] [4 7 9] [4 9 10] [5 10 6]
               [3 5 12] [7 3 11] [9 7 8] [10 9 2]]
        middles {}]
    (var faces faces)
    (fn middle [a b]
      (let [key (.. (math.min a b) " " (math.max a b))]
        (or (. middles key)
            (let [[ax ay az] (. points a) [bx by bz] (. points b)]
              (table.insert points [(/ (+ ax bx) 2) (/ (+ ay by) 2) (/ (+ az bz) 2)])
              (tset middles key (length points))
              (length points)))))
    (for [_ 1 levels]
      (set faces (accumulate [out [] _ [a b c] (ipairs faces)]
                   (let [ab (middle a b) bc (middle b c) ca (middle c a)]
                     (doto out (table.insert [a ab ca]) (table.insert [b bc ab])
                       (table.insert [c ca bc]) (table.insert [ab bc ca]))))))
    {:positions (accumulate [out [] _ [x y z] (ipairs points)]
                  (let [l (/ radius (math.sqrt (+ (* x x) (* y y) (* z z))))]
                    (doto out (table.insert (* x l)) (table.insert (* y l)) (table.insert (* z l)))))
     :triangles (accumulate [out [] _ [a b c] (ipairs faces)]
                  (doto out (table.insert a) (table.insert (if inward? c b))
                    (table.insert (if inward? b c))))}))

(fn joined [a b]
  ;; Two meshes as one, b's vertices after a's.
  (let [n (/ (length a.positions) 3)]
    {:positions (icollect [_ v (ipairs b.positions) &into (icollect [_ v (ipairs a.positions)] v)] v)
     :triangles (icollect [_ v (ipairs b.triangles) &into (icollect [_ v (ipairs a.triangles)] v)]
                  (+ v n))}))

(describe "adaptive meshes"
  (fn []
    (each [_ path (ipairs ["scenes/machined-part.fnl" "scenes/organic.fnl"])]
      (it (.. "give " path " at most half the triangles at the same largest distance from the surface")
        (fn []
          (let [scene (assert (load.load-file path))
                uniform (assert (export.build scene {:resolution 48 :quiet? true}))
                worst (largest-distance scene uniform)
                ;; The simplifier reads the surface about two cells apart, the
                ;; measure a quarter cell apart: half the uniform mesh's distance
                ;; leaves room for what lies between its points.
                adaptive (assert (export.build scene {:resolution 48 :quiet? true
                                                      :adaptive (* 0.5 worst)}))
                n (/ (length uniform.mesh.triangles) 3)
                a (/ (length adaptive.mesh.triangles) 3)]
            (assert.is_true (<= a (* 0.5 n)) (.. a " of " n))
            (assert.are.equal a adaptive.stats.adaptive.after)
            (assert.are.equal n adaptive.stats.adaptive.before)
            (assert.is_true (<= (largest-distance scene adaptive) worst))
            (sound! adaptive.mesh adaptive.grid.h path)
            ;; A collapse moves one end onto the other: every vertex left is one the
            ;; contouring placed, and keeps its colour.
            (let [keys (vertex-keys uniform.mesh)]
              (for [i 1 (length adaptive.mesh.positions) 3]
                (assert.is_true (. keys (string.format "%.17g %.17g %.17g"
                                                       (. adaptive.mesh.positions i)
                                                       (. adaptive.mesh.positions (+ i 1))
                                                       (. adaptive.mesh.positions (+ i 2)))))))
            (assert.are.equal (length adaptive.mesh.positions) (length adaptive.mesh.colors))))))

    (it "turns a box's faces into a few triangles and keeps the border of two materials"
      (fn []
        ;; Two boxes of two colours, overlapping: one solid, its faces flat.
        (let [scene (assert (load.load-string
                             "{:objects [{:kind :box :size [2 1.2 0.8] :pos [0 0 0] :color [0.8 0.3 0.2]}
                                         {:kind :box :size [1 1.2 0.8] :pos [1.4 0 0] :color [0.2 0.3 0.8]}]}"
                             "boxes.fnl"))
              uniform (assert (export.build scene {:resolution 48 :quiet? true}))
              adaptive (assert (export.build scene {:resolution 48 :quiet? true
                                                    :adaptive (* 0.1 uniform.grid.h)}))
              n (/ (length uniform.mesh.triangles) 3)
              a (/ (length adaptive.mesh.triangles) 3)
              keys (vertex-keys adaptive.mesh)
              c uniform.mesh.colors
              p uniform.mesh.positions
              tris uniform.mesh.triangles]
          (assert.is_true (< a (* 0.1 n)) (.. a " of " n))
          (sound! adaptive.mesh adaptive.grid.h "boxes")
          ;; Every end of an edge joining the two colours is still there.
          (var border 0)
          (for [i 1 (length tris) 3]
            (for [k 0 2]
              (let [u (. tris (+ i k)) v (. tris (+ i (% (+ k 1) 3)))]
                (when (not= (. c (* 3 u)) (. c (* 3 v)))
                  (each [_ w (ipairs [u v])]
                    (set border (+ border 1))
                    (assert.is_true (. keys (string.format "%.17g %.17g %.17g" (. p (- (* 3 w) 2))
                                                           (. p (- (* 3 w) 1)) (. p (* 3 w))))))))))
          (assert.is_true (> border 100) (tostring border)))))

    (it "leaves no triangle crossing another where the distance allows anything"
      (fn []
        ;; A shell: a sphere inside another, turned inward, 0.15 apart. With every
        ;; point counted on the surface, only the crossing test keeps the outer
        ;; sphere's flattening triangles off the inner one.
        (let [m (joined (icosphere 1 3 false) (icosphere 0.85 3 true))
              (out stats) (simplify.simplify m 1 0.05 (fn [flat] (fcollect [_ 1 (/ (length flat) 3)] 0)))]
          (assert.is_true (< stats.after (* 0.5 stats.before)) (.. stats.after " of " stats.before))
          (assert.is_true (> stats.crossed 0) "the crossing test refused none")
          (sound! out 0.05 "shell"))))

    (it "refuses a bad --adaptive value with the fix"
      (fn []
        (let [options (require :src.mesh.options)]
          (assert.are.equal 0.01 (options.parse-adaptive "0.01"))
          (each [_ bad (ipairs ["0" "-1" "nan" "1e999" "x"])]
            (let [(v err) (options.parse-adaptive bad)]
              (assert.is_nil v)
              (assert.truthy (err:find "--adaptive must be a distance above 0" 1 true) err))))))))
