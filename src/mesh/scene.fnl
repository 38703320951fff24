;; What `--mesh` meshes of a scene: its finite objects within their bounds, or, with a
;; region given, everything cut by that box; the grid over it; and the CPU evaluator as
;; a field for src/mesh/contour.fnl. Infinite nodes (ground planes, endless repetitions)
;; have no bounds: left out by default, cut by the region when one is given. Pure: runs
;; under plain LuaJIT.

(local plan-mod (require :src.render.plan))
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

(fn select-objects [scene ?region]
  "What to mesh of `scene`: {:scene (the scene with only those objects) :region
{:lo :hi} :cut (the box the field is cut by) :left-out [names] :cut-objects [names]
:message (one line saying which)}, or nil and a message. Without `?region`, the
finite objects within the box around them; with it, every object, the infinite and
those reaching out of the box cut by it."
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
          (let [outside? (fn [b] (accumulate [out? false i (ipairs [1 2 3])]
                                   (or out? (< (. b.hi i) (. ?region.lo i))
                                       (> (. b.lo i) (. ?region.hi i)))))
                cut-objects (icollect [_ o (ipairs ordered)]
                              (let [b (. boxes o.index)]
                                (when (or (not b) (and (not (inside? b ?region))
                                                       (not (outside? b))))
                                  (object-name o))))
                away (icollect [_ o (ipairs ordered)]
                       (let [b (. boxes o.index)] (when (and b (outside? b)) o)))
                gone (collect [_ o (ipairs away)] o.index true)
                sub (collect [k v (pairs scene)] k v)
                parts []]
            (when (< 0 (length cut-objects))
              (table.insert parts (.. "cut by the region: " (table.concat cut-objects ", "))))
            (when (< 0 (length away))
              (table.insert parts (.. "left out, outside the region: "
                                      (table.concat (icollect [_ o (ipairs away)] (object-name o))
                                                    ", "))))
            (set sub.objects (icollect [i o (ipairs scene.objects)] (when (not (. gone i)) o)))
            {:scene sub :region ?region :cut ?region
             :left-out (icollect [_ o (ipairs away)] (object-name o)) : cut-objects
             :message (if (= 0 (length parts))
                          "every object lies within the region"
                          (table.concat parts "; "))})
          (= 0 (length finite))
          (values nil (.. "the scene has no finite objects to mesh ("
                          (table.concat (icollect [_ o (ipairs infinite)] (object-name o)) ", ")
                          " infinite); give --region x0,y0,z0,x1,y1,z1 to mesh them cut by a box"))
          (let [keep (collect [_ o (ipairs finite)] o.index true)
                region {:lo (fcollect [i 1 3]
                              (accumulate [m math.huge _ o (ipairs finite)]
                                (math.min m (. boxes o.index :lo i))))
                        :hi (fcollect [i 1 3]
                              (accumulate [m (- math.huge) _ o (ipairs finite)]
                                (math.max m (. boxes o.index :hi i))))}
                left-out (icollect [_ o (ipairs infinite)] (.. (object-name o) ": infinite"))
                sub (collect [k v (pairs scene)] k v)]
            (set sub.objects (icollect [i o (ipairs scene.objects)] (when (. keep i) o)))
            {:scene sub : region :cut nil : left-out :cut-objects []
             :message (if (= 0 (length left-out))
                          "every object is finite"
                          (.. "left out " (table.concat left-out ", ")
                              " (give --region to mesh them cut by a box)"))})))))

(fn grid-for [selection resolution]
  "The grid of `resolution` cells along the longest side of the selection's region:
{:lo :h :dims :cut} for contour.mesh. Without a given region the cut is the
objects' box grown by a cell (it only closes what their bounds would leave open);
the grid reaches two cells beyond the cut on every side, so its boundary is outside."
  (let [{: lo : hi} selection.region
        longest (math.max (- (. hi 1) (. lo 1)) (- (. hi 2) (. lo 2)) (- (. hi 3) (. lo 3)))
        h (/ longest resolution)
        cut (or selection.cut
                {:lo (fcollect [i 1 3] (- (. lo i) h)) :hi (fcollect [i 1 3] (+ (. hi i) h))})]
    {: h : cut
     :lo (fcollect [i 1 3] (- (. cut.lo i) (* 2 h)))
     :dims (fcollect [i 1 3] (+ 4 (math.ceil (- (/ (- (. cut.hi i) (. cut.lo i)) h) 1e-9))))}))

(fn cpu-field [scene]
  "The CPU evaluator (src/reference.fnl, double precision) of `scene` as a
field for contour.mesh, with :colors (fn [flat n]) -> r g b ... per point (the
material's colour there) and :distance (fn [x y z]) -> d; or nil and a message."
  (case (plan-mod.scene->plan scene {:view :glow :probe? true})
    (nil err) (values nil err)
    plan
    (let [T (reference.tracer scene plan)
          map T.map
          map-color T.map-color]
      {:distances (fn [flat n]
                    (fcollect [k 1 n]
                      (let [b (* 3 (- k 1))]
                        (map (. flat (+ b 1)) (. flat (+ b 2)) (. flat (+ b 3))))))
       :colors (fn [flat n]
                 (let [out []]
                   (for [k 1 n]
                     (let [b (* 3 (- k 1))
                           (_ _ r g bl) (map-color (. flat (+ b 1)) (. flat (+ b 2)) (. flat (+ b 3)))]
                       (tset out (+ b 1) r) (tset out (+ b 2) g) (tset out (+ b 3) bl)))
                   out))
       :distance map
       ;; Double precision: a small step keeps creases sharp.
       :step 1e-4})))

{: select-objects : grid-for : cpu-field
 :parse-region options.parse-region :parse-resolution options.parse-resolution
 :default-resolution options.default-resolution}
