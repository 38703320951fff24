;; The instance-group strategy: objects of one structure (equal lowered code but for
;; their values; lower.fnl's min-group or more) drawn as a loop over their rows in a
;; bank, each member its own object number. A group whose members all have a box has
;; a grid (src/sdf/grid.fnl, made by src/render/plan.fnl): a point then visits only
;; the members its cell lists, and the others' lower bound. See
;; src/sdf/strategies.fnl for the interface.

;; `pairs` under another name: a loop over `pairs` by that name is LuaJIT's ITERN,
;; which Debian 12's LuaJIT ends early once despecialised (see src/util/wire.fnl).
(local each-pair pairs)

(local glsl (require :src.sdf.emit-glsl))
(local emit-lua (require :src.sdf.emit-lua))
(local bounds (require :src.render.bounds))
(local runs (require :src.reference.distance))
(local grid (require :src.sdf.grid))
(local lower (require :src.sdf.lower))
(local chunks (require :src.render.chunks))

(fn group-comment [o]
  (glsl.object-comment o (.. " and " (- o.instances.count 1) " more like it")))

(fn in-group [cx o lines-fn ?slot]
  ;; `(lines-fn cx2)` with cx2 reading `o`'s rows (the group's bank; in a loop over a
  ;; grid cell's list, the first row at the list slot ?slot).
  (lines-fn (glsl.derived cx :group (if ?slot
                                        (doto (collect [k v (each-pair o.instances)] k v) (tset :slot ?slot))
                                        o.instances))))

(fn bank-point [o]
  ;; A group whose bank is in a texture evaluates its members at pg (emit-glsl's reg).
  (if o.instances.texture? ["vec3 pg = p - uBankOrigin;"] []))

(local chunk "shaders/strategies/group.glsl")

(fn looped [cx o block-fn]
  ;; `(block-fn cx2)`'s lines for each member, after the group's comment: in a loop
  ;; over its members, read from its bank; a group with a grid over the members its
  ;; cell at pg lists, after folding the lower bound of the others into d (in
  ;; mapColor too: it lowers d, never the colour, as no surface is nearer than it).
  (let [g o.instances.grid
        block (in-group cx o block-fn (when g "gridStart + k"))]
    [(group-comment o)
     (if g
         (let [names {:grid (tostring g)}]
           (chunks.fill-part chunk :grid
                             {:bank-point (bank-point o)
                              :bound (chunks.fill-part chunk (if cx.along? :bound-along :bound) names)
                              :skip (if cx.along? (chunks.fill-part chunk :skip-along names) [])
                              :member block}))
         (let [loop (chunks.fill-part chunk :loop {:count (tostring o.instances.count) :member block})]
           (if o.instances.texture? (chunks.fill-part chunk :texture-loop {:loop loop}) loop)))]))

(fn block [cx o first materials? open tail]
  ;; Each member's block in a minimum (glsl.object-body), its number first + id + i.
  (let [id (.. (+ first o.id) " + i")]
    (looped cx o #(glsl.object-body $ o id materials? open tail))))

(fn selected [cx o first lines-fn ?var]
  ;; `(lines-fn cx2)`, run when gObject (or the int `?var`) is one of the group's
  ;; numbers, with `i` its member's.
  (let [id (+ first o.id)
        v (or ?var "gObject")]
    [(.. "if (" v " >= " id " && " v " < " (+ id o.instances.count) ") {  " (group-comment o))
     (glsl.indented [(.. "int i = " v (if (= id 0) "" (.. " - " id)) ";")
                     (bank-point o)
                     (in-group cx o lines-fn)])
     "}"]))

;; Its terms as a tree's, from its blocks (each member's, in a loop).
(local written (glsl.written-terms block selected))

(fn grid-of [plan o]
  ;; The group's grid (src/sdf/grid.fnl), or nil.
  (let [g o.instances.grid]
    (when g (. plan.grids.list (+ g 1) :grid))))

{:name :group
 :doc "objects of one structure, a loop over their rows (through a grid when they have boxes)"
 ;; From lower.fnl's min-group on: fewer are written out one by one, as a person
 ;; would (the driver then has no loop to unroll; llvmpipe leaves some unrolled).
 :takes? (fn [count] (>= count lower.min-group))
 :rank 10
 :gathers? true
 :key (fn [key count] (.. "group:" count "[" key "]"))
 :count (fn [o] o.instances.count)
 :folds? false
 :marched? (fn [o] (not o.half-space?))
 :infos (fn [o] o.infos)
 :describe (fn [o] (.. " x" o.instances.count " (instance group: a loop)"))
 :glsl (doto written
         ;; Two forms: the whole group's minimum but member `skip`, and member
         ;; `only`'s distance; with `materials`, mapColor's term.
         (tset :object (fn [cx o first mirrors? modern?]
                         (glsl.either-terms
                          (written.color cx o first mirrors? modern?)
                          ["if (all) {"
                           (glsl.indented (block cx o first false #(.. "if (skip != " $ ") {")
                                                 (glsl.minimum-tail o)))
                           "}"
                           (selected cx o first
                                     #[(glsl.emit-code $ [] o.code false) (.. "d = " o.dout ";")]
                                     "only")])))
         (tset :planes (fn [cx o] (when o.half-space? (looped cx o (glsl.plane-block o))))))
 :lua (fn [tape o what banks into] (emit-lua.object-evaluators tape o what banks into o.instances))
 :spheres (fn [plan o at out]
            (let [g (grid-of plan o)
                  n o.instances.count]
              (if g
                  (table.insert out (bounds.grid-sphere g))
                  (for [m 1 n]
                    (when (not o.half-space?)
                      (table.insert out (or (bounds.object-sphere (. plan.objects (+ at m)) (. o.infos m))
                                            false)))))
              (+ at n)))
 :run (fn [plan o run] (doto run (tset :grid (grid-of plan o))))
 ;; A grid (src/render/plan.fnl's grids-of) for a group of grid.min-members or more
 ;; whose members all have a box: their boxes and the bank's layout, the group marked
 ;; as grid `number`; then its bank is read from a texture.
 :grid-boxes (fn [o number]
               (when (and (>= o.instances.count grid.min-members) (not o.half-space?))
                 (let [boxes (icollect [_ info (ipairs o.infos)] (when (not info.large?) info.box))]
                   (when (= (length boxes) o.instances.count)
                     (set o.instances.grid number)
                     (values boxes o.instances)))))
 :bank-in-texture! (fn [o] (set o.instances.texture? true))
 :reference {:min runs.grid-min :color runs.grid-color :near runs.grid-near}}
