;; What `--mesh` meshes of a scene: its finite objects within their bounds, or, with a
;; region given, everything cut by that box; the grid over it; and the CPU evaluator as
;; a field for src/mesh/contour.fnl. Infinite nodes (ground planes, endless repetitions)
;; have no bounds: left out by default, cut by the region when one is given. The grid
;; follows what is there: a region is clipped to the box around the objects in it
;; (memory and time follow the content, not the region's volume). Pure: runs under
;; plain LuaJIT.

;; `pairs` under another name: a loop over `pairs` by that name is LuaJIT's ITERN,
;; which Debian 12's LuaJIT ends early once despecialised (see src/util/wire.fnl).
(local each-pair pairs)

(local plan-mod (require :src.render.plan))
(local fork (require :src.util.fork))
(local reference (require :src.reference))
(local lower (require :src.sdf.lower))

(local options (require :src.mesh.options))

(fn object-box [o infos]
  "The world box {:lo :hi} of plan object `o`, or nil when it is infinite."
  (if o.tree (?. infos o.index :box)
      (= o.kind :sphere) (let [[x y z] o.pos r o.radius]
                           {:lo [(- x r) (- y r) (- z r)] :hi [(+ x r) (+ y r) (+ z r)]})
      (= o.kind :box) (let [[x y z] o.pos [sx sy sz] o.size]
                        {:lo [(- x (* 0.5 sx)) (- y (* 0.5 sy)) (- z (* 0.5 sz))]
                         :hi [(+ x (* 0.5 sx)) (+ y (* 0.5 sy)) (+ z (* 0.5 sz))]})
      nil))

(fn object-name [o]
  (string.format "objects[%d] (%s)" o.index o.kind))

(fn inside? [box region]
  (accumulate [ok? true i (ipairs [1 2 3])]
    (and ok? (>= (. box.lo i) (. region.lo i)) (<= (. box.hi i) (. region.hi i)))))

;; The box an infinite object (a ground plane, an endless repetition) is taken to
;; fill when a region cuts it: the coordinates a scene may have (src/scene/load.fnl's
;; limits.world), so a region past them meshes what a scene can hold.
(local world 1e7)

(fn box-text [b]
  (string.format "%.4g,%.4g,%.4g,%.4g,%.4g,%.4g" (. b.lo 1) (. b.lo 2) (. b.lo 3)
                 (. b.hi 1) (. b.hi 2) (. b.hi 3)))

(fn far-sighted [scene region]
  "`scene` (a shallow copy) with a draw distance past `region`'s diagonal: the CPU
evaluator and the shader report no distance above the draw distance, and the
mesher's octree skips a block only when the distance at its centre exceeds its
half-diagonal, so with the cap inside the grid it would sample the whole volume."
  (let [diagonal (math.sqrt (accumulate [s 0 i (ipairs [1 2 3])]
                              (+ s (^ (- (. region.hi i) (. region.lo i)) 2))))
        render (collect [k v (each-pair (or scene.render {}))] k v)
        sub (collect [k v (each-pair scene)] k v)]
    (set render.draw-distance (math.max (or render.draw-distance 0) (* 2 diagonal)))
    (set sub.render render)
    sub))

(fn clip [region objects boxes]
  "`region` clipped to the box around `objects` (those not outside it): the finite
ones' boxes, and the world box (±world) when one is infinite. Never empty: every
object in `objects` reaches into the region."
  (let [bound {:lo [math.huge math.huge math.huge]
               :hi [(- math.huge) (- math.huge) (- math.huge)]}]
    (each [_ o (ipairs objects)]
      (let [b (or (. boxes o.index) {:lo [(- world) (- world) (- world)]
                                     :hi [world world world]})]
        (for [i 1 3]
          (tset bound.lo i (math.min (. bound.lo i) (. b.lo i)))
          (tset bound.hi i (math.max (. bound.hi i) (. b.hi i))))))
    {:lo (fcollect [i 1 3] (math.max (. region.lo i) (. bound.lo i)))
     :hi (fcollect [i 1 3] (math.min (. region.hi i) (. bound.hi i)))}))

(fn select-objects [scene ?region]
  "What to mesh of `scene`: {:scene (the scene with only those objects) :region
{:lo :hi} (the box the grid is sized by) :cut (nil, or the box the field is cut by:
the given region, within ±1e7 when an infinite object is in it) :left-out [names] :cut-objects [names] :message (one line saying
which)}, or nil and a message. Without `?region`, the finite objects within the box
around them; with it, every object that reaches into it, the infinite and those
reaching out of it cut by it. The grid is sized by what is there, not by the region:
the region is clipped to the box around the objects in it (an infinite one, which
has no box, counts as the ±1e7 a scene's coordinates lie within), so a region of
1e30 around a box meshes the box as its own box would."
  (case (plan-mod.scene->plan scene {:view :glow :probe? true})
    (nil err) (values nil err)
    plan
    (let [infos (lower.infos-by-index plan.tape)
          boxes (collect [_ o (ipairs plan.objects)] o.index (or (object-box o infos) false))
          ordered (doto (icollect [_ o (ipairs plan.objects)] o)
                    (table.sort (fn [a b] (< a.index b.index))))
          finite (icollect [_ o (ipairs ordered)] (when (. boxes o.index) o))
          infinite (icollect [_ o (ipairs ordered)] (when (not (. boxes o.index)) o))]
      (if ?region
          ;; Touching the region is not reaching into it: nothing of it is inside.
          (let [outside? (fn [b] (accumulate [out? false i (ipairs [1 2 3])]
                                   (or out? (<= (. b.hi i) (. ?region.lo i))
                                       (>= (. b.lo i) (. ?region.hi i)))))
                cut-objects (icollect [_ o (ipairs ordered)]
                              (let [b (. boxes o.index)]
                                (when (or (not b) (and (not (inside? b ?region))
                                                       (not (outside? b))))
                                  (object-name o))))
                away (icollect [_ o (ipairs ordered)]
                       (let [b (. boxes o.index)] (when (and b (outside? b)) o)))
                gone (collect [_ o (ipairs away)] o.index true)
                kept (icollect [_ o (ipairs ordered)] (when (not (. gone o.index)) o))
                away-text (.. "left out, outside the region: "
                              (table.concat (icollect [_ o (ipairs away)] (object-name o))
                                            ", "))
                sub (collect [k v (each-pair scene)] k v)
                parts []]
            (if (= 0 (length kept))
                (values nil (.. "no surface to mesh: " away-text
                                " (is the region clear of every object?)"))
                (let [region (clip ?region kept boxes)
                      clipped? (accumulate [c? false i (ipairs [1 2 3])]
                                 (or c? (> (. region.lo i) (. ?region.lo i))
                                     (< (. region.hi i) (. ?region.hi i))))]
                  (when (< 0 (length cut-objects))
                    (table.insert parts (.. "cut by the region: " (table.concat cut-objects ", "))))
                  (when (< 0 (length away)) (table.insert parts away-text))
                  (when (= 0 (length parts))
                    (table.insert parts "every object lies within the region"))
                  (when clipped?
                    (table.insert parts
                                  (.. "the grid spans " (box-text region)
                                      (if (< 0 (length infinite))
                                          ", the region clipped to the objects' box (an infinite object's: ±1e7, the coordinates a scene may have)"
                                          ", the region clipped to the objects' box"))))
                  (set sub.objects (icollect [i o (ipairs scene.objects)] (when (not (. gone i)) o)))
                  {:scene (far-sighted sub region) : region
                   ;; An infinite object is cut by the world box too.
                   :cut (if (= 0 (length infinite)) ?region
                            {:lo (fcollect [i 1 3] (math.max (. ?region.lo i) (- world)))
                             :hi (fcollect [i 1 3] (math.min (. ?region.hi i) world))})
                   :left-out (icollect [_ o (ipairs away)] (object-name o)) : cut-objects
                   :message (table.concat parts "; ")})))
          (= 0 (length finite))
          (values nil (.. "the scene has no finite objects to mesh ("
                          (table.concat (icollect [_ o (ipairs infinite)] (object-name o)) ", ")
                          " infinite); give --region x0,y0,z0,x1,y1,z1 to mesh them cut by a box"))
          (let [keep (collect [_ o (ipairs finite)] o.index true)
                region (clip {:lo [(- math.huge) (- math.huge) (- math.huge)]
                              :hi [math.huge math.huge math.huge]}
                             finite boxes)
                left-out (icollect [_ o (ipairs infinite)] (.. (object-name o) ": infinite"))
                sub (collect [k v (each-pair scene)] k v)]
            (set sub.objects (icollect [i o (ipairs scene.objects)] (when (. keep i) o)))
            {:scene (far-sighted sub region) : region :cut nil : left-out :cut-objects []
             :message (if (= 0 (length left-out))
                          "every object is finite"
                          (.. "left out " (table.concat left-out ", ")
                              " (give --region to mesh them cut by a box)"))})))))

(fn grid-for [selection resolution]
  "The grid of `resolution` cells along the longest side of the selection's region:
{:lo :h :dims :cut} for contour.mesh. The cut is the region grown by a cell (it
only closes what the objects' bounds would leave open), within the given region
when there is one (a region clipped to the objects' box is then cut where they are
cut, and where they are not as without a region); the grid reaches two cells beyond
the cut on every side, so its boundary is outside."
  (let [{: lo : hi} selection.region
        longest (math.max (- (. hi 1) (. lo 1)) (- (. hi 2) (. lo 2)) (- (. hi 3) (. lo 3)))
        h (/ longest resolution)
        given selection.cut
        cut {:lo (fcollect [i 1 3] (math.max (- (. lo i) h) (if given (. given.lo i) (- math.huge))))
             :hi (fcollect [i 1 3] (math.min (+ (. hi i) h) (if given (. given.hi i) math.huge)))}]
    {: h : cut :max-leaves options.max-leaves
     :lo (fcollect [i 1 3] (- (. cut.lo i) (* 2 h)))
     :dims (fcollect [i 1 3] (+ 4 (math.ceil (- (/ (- (. cut.hi i) (. cut.lo i)) h) 1e-9))))}))

;; The level set meshed, in cells: the field's at minus this (contour.mesh's
;; :offset; the GPU's field, src/mesh/gpu.fnl, takes the same). A grid point is
;; inside where d < -offset. A face on a grid plane (the region's bounds are, and
;; the cut's) has d = 0 at its grid points up to rounding, and which way that
;; rounding went put the point in or out: double on the CPU, float32 on the GPU
;; (coordinates and arithmetic), so the two meshes of one scene differed
;; (platonic-shelf at 128: 36540 and 35492 triangles, a board's front face on a
;; grid plane; machined-part at 64: 9348 and 9284, the CPU's reproduced by
;; rounding its points to float32). Float32's rounding is some 1e-7 of a
;; coordinate, 1e-5 of a cell at 128 cells across a scene near the origin; a
;; thousandth of a cell puts those points outside on both. The surface moves
;; inward by as much, a tenth of the sharp-feature tests' 0.01 cell.
(local surface-offset 1e-3)

(fn cpu-field [scene ?workers]
  "The CPU evaluator (src/reference.fnl, double precision) of `scene` as a
field for contour.mesh (:distances (fn [flat n ?skip]), see contour.mesh), with
:colors (fn [flat n]) -> r g b ... per point (the
material's colour there) and :distance (fn [x y z]) -> d; or nil and a message.
A batch of points is shared among ?workers processes (default: one per core) when
it is worth the forks (see src/util/fork.fnl); the numbers are the same as one's."
  (case (plan-mod.scene->plan scene {:view :glow :probe? true})
    (nil err) (values nil err)
    plan
    (let [T (reference.tracer scene plan)
          map T.map
          map-color T.map-color
          split-distances (fork.splitter ?workers)
          split-colours (fork.splitter ?workers)]
      {:distances (fn [flat n ?skip]
                    (split-distances n 1
                                      (fn [first last out]
                                        (for [k first last]
                                          (let [b (* 3 (+ k (or ?skip 0) -1))]
                                            (tset out k (map (. flat (+ b 1)) (. flat (+ b 2))
                                                             (. flat (+ b 3)))))))))
       :colors (fn [flat n]
                 (split-colours n 3
                                   (fn [first last out]
                                     (for [k first last]
                                       (let [b (* 3 (- k 1))
                                             (_ _ r g bl) (map-color (. flat (+ b 1)) (. flat (+ b 2))
                                                                     (. flat (+ b 3)))]
                                         (tset out (+ b 1) r) (tset out (+ b 2) g)
                                         (tset out (+ b 3) bl))))))
       :distance map
       ;; It may run in a forked child (src/util/fork.fnl): the mesher's shares.
       :fork-safe? true
       ;; Double precision: a small step keeps creases sharp.
       :step 1e-4
       :offset surface-offset})))

{: select-objects : grid-for : cpu-field : surface-offset
 :parse-region options.parse-region :parse-resolution options.parse-resolution
 :default-resolution options.default-resolution}
