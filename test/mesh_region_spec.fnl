;; tier: fast
;; --mesh's grid follows the scene's content, not the region's volume (issue 43): a
;; region is clipped to the box around the objects in it (src/mesh/scene.fnl), so a
;; region of 1e30 around a box meshes the same triangles as the box's own bounds, and
;; an infinite object counts as filling ±1e7 (the coordinates a scene may have).
;; Degenerate regions are refused with a message. Plain LuaJIT, small resolutions;
;; no timing decides a verdict.

(local load (require :src.scene.load))
(local export (require :src.mesh.export))
(local check (require :src.mesh.check))
(local mesh-scene (require :src.mesh.scene))
(local options (require :src.mesh.options))

(fn scene-of [objects]
  (assert (load.load-string (.. "{:objects [" objects "]}") "mesh-region-test")))

(fn build [scene resolution ?region]
  (assert (export.build scene {:resolution resolution :region ?region :quiet? true})))

(fn region [s] (assert (options.parse-region s)))

(fn same-mesh [a b what]
  (assert.are.same a.grid b.grid (.. what ": grid"))
  (assert.are.equal (length a.mesh.triangles) (length b.mesh.triangles) (.. what ": triangles"))
  (assert.are.same a.mesh.triangles b.mesh.triangles (.. what ": triangle indices"))
  (assert.are.same a.mesh.positions b.mesh.positions (.. what ": positions")))

(describe "a region clipped to the scene's content"
  (fn []
    (local two (scene-of (.. "{:kind :box :size [1 2 1] :pos [0 0 0.5]} "
                             "{:kind :sphere :radius 0.6 :pos [1.5 0 0.4]}")))

    (it "meshes the same triangles under a huge region as under the objects' own box"
      (fn []
        (let [own (build two 24)]
          (each [_ text (ipairs ["-1e30,-1e30,-1e30,1e30,1e30,1e30"
                                 "-1e300,-5,-5,1e300,5,1e308"
                                 "-10,-10,-10,10,10,10"])]
            (let [r (build two 24 (region text))]
              (same-mesh own r text)
              (assert.truthy (r.message:find "the region clipped to the objects' box" 1 true)
                             r.message)
              (assert.is_true (. (check.topology r.mesh) :manifold?) text))))))

    (it "sizes the grid by the content: a huge region gives the box's grid, not the region's"
      (fn []
        (let [sel (assert (mesh-scene.select-objects two (region "-1e30,-1e30,-1e30,1e30,1e30,1e30")))
              own (assert (mesh-scene.select-objects two))
              grid (mesh-scene.grid-for sel 24)]
          (assert.are.same own.region sel.region)
          (assert.are.same (mesh-scene.grid-for own 24) grid)
          ;; 24 cells along the longest side (2.6), and two and a cell each side.
          (assert.is_true (< (math.abs (- grid.h (/ 2.6 24))) 1e-12) (tostring grid.h))
          (assert.is_true (<= (. grid.dims 1) 30) (table.concat grid.dims "x")))))

    (it "still cuts the objects the region cuts, where it cuts them"
      (fn []
        (let [r (build two 24 (region "-1e30,-1e30,-1e30,1e30,1e30,0.5"))]
          (assert.are.equal 0.5 (. r.grid.cut :hi 3))
          (assert.truthy (r.message:find "cut by the region: objects[1] (box), objects[2] (sphere)" 1 true)
                         r.message)
          (assert.is_true (. (check.topology r.mesh) :manifold?))
          ;; Every vertex at the cut or below it (within a tenth of a cell: the
          ;; vertices of the cut's edges are where the tangent planes meet).
          (for [q 3 (length r.mesh.positions) 3]
            (assert.is_true (<= (. r.mesh.positions q) (+ 0.5 (* 0.1 r.grid.h)))
                            (tostring (. r.mesh.positions q)))))))

    (it "takes an infinite object to fill ±1e7, and says so"
      (fn []
        (let [s (scene-of "{:kind :plane :height 0} {:kind :sphere :radius 0.5 :pos [0 0 3]}")
              r (build s 16 (region "-1e30,-1e30,-1e30,1e30,1e30,1e30"))]
          (assert.are.same {:lo [-1e7 -1e7 -1e7] :hi [1e7 1e7 1e7]} r.grid.cut)
          (assert.truthy (r.message:find "cut by the region: objects[1] (plane)" 1 true) r.message)
          (assert.truthy (r.message:find "an infinite object's: ±1e7" 1 true) r.message)
          (assert.is_true (. (check.topology r.mesh) :manifold?)))
        ;; Within ±1e7 the region is the plane's bound, as before: no clipping said.
        (let [s (scene-of "{:kind :plane :height 0}")
              r (build s 16 (region "-2,-2,-1,2,2,1"))]
          (assert.are.equal "cut by the region: objects[1] (plane)" r.message))))

    (it "refuses a resolution whose surface would take too much memory, before sampling it"
      (fn []
        ;; A unit box at 768 cells: 221,186 leaf blocks (at 704, 186,000 took 4.0
        ;; GB); refused once the octree has counted them, with a resolution that
        ;; fits.
        (let [box (scene-of "{:kind :box :size [1 1 1]}")
              (r err) (export.build box {:quiet? true :resolution 768})]
          (assert.is_nil r)
          (assert.are.equal "the surface at 768 cells fills 221186 blocks of 4x4x4 cells, more than the 180224 one mesh may have (memory follows them, up to about 3.9 GB at that many); give --resolution 616 or less"
                            err))
        ;; The mesher's own limit: raised before any corner is sampled.
        (let [contour (require :src.mesh.contour)
              sel (assert (mesh-scene.select-objects two))
              grid (doto (mesh-scene.grid-for sel 24) (tset :max-leaves 10))
              field (assert (mesh-scene.cpu-field sel.scene))
              points []
              (ok? e) (pcall contour.mesh field grid
                             (fn [phase _ _ n] (tset points phase n)))]
          (assert.is_false ok?)
          (assert.are.equal 10 e.max-leaves)
          (assert.is_true (> e.leaves 10))
          (assert.is_nil points.corners))))

    (it "refuses a region clear of every object before meshing, and degenerate regions"
      (fn []
        (let [(r err) (export.build two {:quiet? true :region (region "5,5,5,1e30,1e30,1e30")})]
          (assert.is_nil r)
          (assert.are.equal "no surface to mesh: left out, outside the region: objects[1] (box), objects[2] (sphere) (is the region clear of every object?)"
                            err))
        ;; Touching a box's face is not reaching into it.
        (let [(r err) (export.build two {:quiet? true :region (region "-5,-5,1,5,5,2")})]
          (assert.is_nil r)
          (assert.truthy (err:find "is the region clear of every object" 1 true) err))
        (each [_ [text message]
               (ipairs [["0,0,0,0,1,1" "--region: x1 must be greater than x0, got 0,0,0,0,1,1"]
                        ["0,0,0,1,-1,1" "--region: y1 must be greater than y0, got 0,0,0,1,-1,1"]
                        ["0,0,5,1,1,5" "--region: z1 must be greater than z0, got 0,0,5,1,1,5"]
                        ["nan,0,0,1,1,1" "--region must be six numbers x0,y0,z0,x1,y1,z1, got nan,0,0,1,1,1"]
                        ["0,0,0,inf,1,1" "--region must be six numbers x0,y0,z0,x1,y1,z1, got 0,0,0,inf,1,1"]
                        ["-1e999,0,0,1,1,1" "--region must be six numbers x0,y0,z0,x1,y1,z1, got -1e999,0,0,1,1,1"]
                        ["0,0,0,1,1,1,1" "--region must be six numbers x0,y0,z0,x1,y1,z1, got 0,0,0,1,1,1,1"]])]
          (let [(r err) (options.parse-region text)]
            (assert.is_nil r text)
            (assert.are.equal message err)))
        (each [_ text (ipairs ["1e9" "1025" "1e999" "nan" "-128" "0x10000" "7"])]
          (let [(r err) (options.parse-resolution text)]
            (assert.is_nil r text)
            (assert.are.equal (.. "--resolution must be a whole number from 8 to 1024, got " text) err)))))))
