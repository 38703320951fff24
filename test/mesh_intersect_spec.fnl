;; tier: fast
;; Self-intersections of a mesh (issue 46): src/mesh/intersect.fnl's exact test of a
;; pair of triangles on constructed cases whose answer is known by hand, and its
;; count over a mesh (the broad phase finds every pair once). The meshes of scenes
;; are checked in test/mesh_spec.fnl.

(local intersect (require :src.mesh.intersect))

(fn mesh-of [...]
  "A mesh of the given triangles, each [x y z x y z x y z], no vertex shared."
  (let [positions [] triangles []]
    (each [_ t (ipairs [...])]
      (let [n (/ (length positions) 3)]
        (each [_ v (ipairs t)] (table.insert positions v))
        (for [c 1 3] (table.insert triangles (+ n c)))))
    {: positions : triangles}))

(fn near [want got what]
  ;; Lengths worked out by hand; 1e-12 is rounding on numbers of size 1.
  (assert.is_true (< (math.abs (- want got)) 1e-12)
                  (string.format "%s: want %.15g, got %.15g" what want got)))

(local base [0 0 0 2 0 0 0 2 0])

(fn apart-both-ways [p-text q-text]
  "Two triangles, each nine numbers in text, share nothing beyond a point, either
way round. Read from text: Fennel writes number literals into Lua with 14 digits,
which would move the vertices off the plane they share."
  (let [tri (fn [text] (icollect [w (text:gmatch "%S+")] (tonumber w)))
        p (tri p-text)
        q (tri q-text)]
    (assert.are.equal 0 (intersect.pair-overlap p q))
    (assert.are.equal 0 (intersect.pair-overlap q p))))

(describe "triangle self-intersections"
  (fn []
    (it "measures the segment two crossing triangles share"
      (fn []
        ;; A vertical triangle through the base: it crosses z = 0 along y = 0.5
        ;; from x = 0.5 to x = 1.5, all inside the base (x + y < 2 there).
        (let [(len kind) (intersect.pair-overlap base [0.5 0.5 -1 0.5 0.5 1 2.5 0.5 0])]
          (near 1 len "crossing") (assert.are.equal :crossing kind))
        ;; The same crossing, the other way round and with the base wound the
        ;; other way: the same segment.
        (near 1 (intersect.pair-overlap [0.5 0.5 -1 0.5 0.5 1 2.5 0.5 0]
                                        [0 0 0 0 2 0 2 0 0])
              "swapped")
        ;; One that pierces it only partly: the cut from x = 1 to 2.5 along
        ;; y = 0.5 leaves the base at x = 1.5.
        (near 0.5 (intersect.pair-overlap base [1 0.5 -1 1 0.5 1 4 0.5 0]) "part")))

    (it "counts nothing where triangles only touch or are apart"
      (fn []
        ;; A vertex on the base's face; an edge lying on it counts as a segment
        ;; of contact (a mesh touching itself), a vertex does not.
        (assert.are.equal 0 (intersect.pair-overlap base [0.5 0.5 0 0.5 0.5 1 1.5 0.5 1]))
        ;; Above it, parallel.
        (assert.are.equal 0 (intersect.pair-overlap base [0 0 1 2 0 1 0 2 1]))
        ;; Crossing the base's plane, but beside the base.
        (assert.are.equal 0 (intersect.pair-overlap base [3 0.5 -1 3 0.5 1 4 0.5 0]))
        ;; Coplanar, beside it, and coplanar along its hypotenuse (touching along
        ;; an edge: no area in common).
        (assert.are.equal 0 (intersect.pair-overlap base [3 0 0 4 2 0 3 2 0]))
        (assert.are.equal 0 (intersect.pair-overlap base [2 0 0 0 2 0 2 2 0]))))

    (it "measures coplanar triangles that overlap"
      (fn []
        ;; A small triangle inside the base: their common part is the small one,
        ;; whose diameter is its hypotenuse, sqrt(0.5).
        (let [(len kind) (intersect.pair-overlap base [0.5 0.5 0 1 0.5 0 0.5 1 0])]
          (near (math.sqrt 0.5) len "inside")
          (assert.are.equal :coplanar kind))
        ;; Tilted out of every coordinate plane: the same, measured in its plane.
        (let [turn (fn [x y z] [(/ (+ x z) (math.sqrt 2)) y (/ (- z x) (math.sqrt 2))])
              tri (fn [t] (let [out []]
                            (for [b 0 6 3]
                              (each [_ v (ipairs (turn (. t (+ b 1)) (. t (+ b 2)) (. t (+ b 3))))]
                                (table.insert out v)))
                            out))]
          (near (math.sqrt 0.5) (intersect.pair-overlap (tri base) (tri [0.5 0.5 0 1 0.5 0 0.5 1 0]))
                "tilted"))))

    (it "counts crossing pairs in a mesh, not neighbours sharing an edge or a vertex"
      (fn []
        ;; Two crossing triangles and one far away: one pair.
        (let [r (intersect.self-intersections
                 (mesh-of base [0.5 0.5 -1 0.5 0.5 1 2.5 0.5 0] [10 10 10 11 10 10 10 11 10]))]
          (assert.are.equal 1 r.pairs)
          (near 1 r.longest "longest")
          (assert.are.same [0 1] [(. r.list 1 1) (. r.list 1 2)]))
        ;; Two triangles sharing an edge (a folded square) and a fan of four
        ;; sharing a vertex, all indexed: nothing crosses.
        (let [r (intersect.self-intersections
                 {:positions [0 0 0 1 0 0 1 1 0.5 0 1 0 -1 0 0 0 -1 0]
                  :triangles [1 2 3 1 3 4 1 4 5 1 5 6 1 6 2]})]
          (assert.are.equal 0 r.pairs)
          (assert.are.equal 0 r.folds))
        ;; Two triangles sharing a vertex, one folded through the other: they meet
        ;; along more than the vertex, counted apart (:folds) from the crossings.
        (let [r (intersect.self-intersections
                 {:positions [0 0 0 2 0 0 0 2 0 1 1 -1 1 0.2 1]
                  :triangles [1 2 3 1 4 5]})]
          (assert.are.equal 0 r.pairs)
          (assert.are.equal 1 r.folds))))

    (it "finds no crossing between nearly coplanar neighbours of a flat face"
      (fn []
        ;; Two triangles of platonic-shelf's prism at 128 cells, on one flat face
        ;; up to rounding: the first spans y from -0.1695 to -0.0836, the second
        ;; from -0.0836 to 0.0023, and at y = -0.0836 the first is one point
        ;; beside the second's edge. The line where their planes meet is
        ;; ill-defined; a test that trusted it found them crossing 0.03 cells.
        (apart-both-ways "-3.5344056822027952 -0.16953124999999991 1.7939974488419144 -3.5701818837848327 -0.083593749999999911 1.7320312499999999 -3.5701818837848025 -0.16953124999999991 1.7320312499999826"
                         "-3.5344056822027952 -0.083593749999999911 1.7939974488419144 -3.5095976628235439 -0.083593749999999911 1.8369661988419086 -3.5095976628235275 0.0023437500000000888 1.8369661988418988")))

    (it "finds no fold between nearly coplanar triangles on opposite sides of their vertex"
      (fn []
        ;; Two triangles of one flat fan of platonic-shelf at 128 cells: the
        ;; first below their common vertex, the second above it, in one vertical
        ;; plane but for 1e-13 of a coordinate. The planes' line through the
        ;; vertex is ill-defined; cutting along it found a fold of half a cell.
        (apart-both-ways "2.3526647973759642 -0.49030731939245586 4.3101562500000004 2.3526647973759642 -0.49030731939245586 4.3960937500000004 2.2831398994219008 -0.53327606939251071 4.3960937500000004"
                         "2.3526647973759642 -0.49030731939245586 4.3960937500000004 2.395633547375998 -0.46375117143841371 4.4820312500000004 2.3526647973760046 -0.49030731939252126 4.4820312500000004")))

    (it "still finds triangles crossing at a tiny angle, as an overlap in their plane"
      (fn []
        ;; The base and a copy turned by 1e-8 radians about the line y = 0.5
        ;; and shifted by half along x: they cross along that line, and seen
        ;; along the normal they overlap in a triangle of legs 1 and 1.
        (let [a 1e-8
              turn (fn [x y] [(+ x 0.5) y (* (- y 0.5) (math.sin a))])
              q (let [out []]
                  (each [_ [x y] (ipairs [[0 0] [2 0] [0 2]])]
                    (each [_ v (ipairs (turn x y))] (table.insert out v)))
                  out)
              (len kind) (intersect.pair-overlap base q)]
          (assert.is_true (> len 1) (string.format "overlap %.3g" len))
          (assert.are.equal :coplanar kind))))

    (it "finds folds through each vertex's own triangles, and none in a flat or bent fan"
      (fn []
        ;; A fan of six around the origin, flat, then bent into a cone: an
        ;; umbrella, no fold. Then one triangle turned over onto its neighbour's
        ;; side: a fold at the shared vertex, found by folds as by
        ;; self-intersections.
        (let [ring (fcollect [k 0 5]
                     (let [t (* k (/ math.pi 3))] [(math.cos t) (math.sin t)]))
              fan (fn [height]
                    ;; The centre, then the ring at `height`.
                    (let [positions [0 0 0]]
                      (each [_ [x y] (ipairs ring)]
                        (table.insert positions x) (table.insert positions y)
                        (table.insert positions height))
                      positions))
              tris (fn [] (let [out []]
                            (for [k 1 6]
                              (table.insert out 1) (table.insert out (+ k 1))
                              (table.insert out (+ (% k 6) 2)))
                            out))]
          (each [_ height (ipairs [0 0.4 -0.7])]
            (let [m {:positions (fan height) :triangles (tris)}]
              (assert.are.same [] (intersect.folds m) (.. "height " height))))
          ;; Vertex 3 (ring point 2) pulled across, in the plane, to (-0.9 -0.5):
          ;; the triangles 1-2-3 and 1-3-4 turn over and lie on 1-5-6 and 1-6-7.
          (let [m {:positions (fan 0) :triangles (tris)}]
            (tset m.positions 7 -0.9) (tset m.positions 8 -0.5)
            (let [folds (intersect.folds m)
                  r (intersect.self-intersections m)]
              (assert.is_true (> (length folds) 0))
              (assert.are.equal r.folds (length folds))))
          ;; A fan that does not close: a quarter and a quarter, then two
          ;; panels that overlap each other (200-300 and 250-350 degrees). A
          ;; direction in the first panel is covered once, but the fan is no
          ;; umbrella: its pairs are tested, and the overlap found.
          (let [at (fn [degrees] (let [t (math.rad degrees)] [(math.cos t) (math.sin t) 0]))
                positions [0 0 0]]
            (each [_ d (ipairs [0 90 180 200 300 250 350])]
              (each [_ c (ipairs (at d))] (table.insert positions c)))
            (let [m {: positions :triangles [1 2 3 1 3 4 1 5 6 1 7 8]}]
              (assert.are.equal 1 (length (intersect.folds m)))
              ;; A vertex no triangle uses, last: no fan to look around.
              (each [_ c (ipairs [5 5 5])] (table.insert positions c))
              (assert.are.equal 1 (length (intersect.folds m)))
              (assert.are.equal 1 (. (intersect.self-intersections m) :folds)))))))

    (it "finds every crossing pair of a grid of triangles, each pair once"
      (fn []
        ;; n x n small horizontal triangles, and n vertical ones each piercing
        ;; one row of them: n crossings per vertical triangle, which cuts z = 0
        ;; from x = -1.375 n to 2.375 n along y = j + 0.25, through the n
        ;; horizontal ones of row j (each spans x from i to i + 0.9, y from j to
        ;; j + 0.9 - (x - i): the line crosses it from x = i to i + 0.65).
        (let [n 12
              tris []]
          (for [j 0 (- n 1)]
            (for [i 0 (- n 1)]
              (table.insert tris [i j 0 (+ i 0.9) j 0 i (+ j 0.9) 0])))
          (for [j 0 (- n 1)]
            (table.insert tris [(* -2 n) (+ j 0.25) -0.5 (* 3 n) (+ j 0.25) -0.5
                                (* 0.5 n) (+ j 0.25) 1.5]))
          (let [r (intersect.self-intersections (mesh-of (unpack tris)) {:max-list 1000})
                seen {}]
            (assert.are.equal (* n n) r.pairs)
            (near 0.65 r.longest "longest")
            (each [_ [s t] (ipairs r.list)]
              (let [k (.. s " " t)]
                (assert.is_nil (. seen k) k)
                (tset seen k true)))))))))
