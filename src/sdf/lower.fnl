;; Lowering: validated scene-tree objects become one flat tape, the intermediate form
;; that both the GLSL emitter (src/sdf/emit-glsl.fnl) and the CPU evaluator
;; (src/sdf/emit-lua.fnl) read, so the two cannot drift apart.
;;
;; A tape is plain data:
;;   :objects  one entry per top-level tree object: {:index (scene index) :code [...]
;;             :dout (distance register) :mout (material register) :info (node info)}
;;   :rows     parameter values, four numbers per row (the GLSL sees vec4 uTape[rows])
;;   :relative rows whose xyz are world positions, made camera-relative on upload
;;   :inner    {:root t :translations [row ...] :planes [{:row r :height ref} ...]}
;;             for each object whose camera offset is taken off one level in (see
;;             `hand-in`): on upload its translation's row t is 0, and those rows
;;             (a plane's height, in argument `ref`) take the camera off instead
;;   :used     descriptor names the code calls (the GLSL holds only those)
;;   :key      the structure: equal keys mean the same generated code
;;   :mirrors? whether any material is less than a full mirror
;;   :estimates? whether an argument takes another value where the field is read as
;;             an estimate of the distance (a soft shadow's penumbra, occlusion) than
;;             where a march steps by it: the argument after one marked :estimate?
;;             (a custom node declared steeper than it measured; src/sdf/custom.fnl)
;; Instructions (registers: p points, d distances, m materials, numbered per tape):
;;   {:op :prim :desc D :args A :pin p :dout d}      d = D(p, args)
;;   {:op :point :desc D :args A :pin p :pout p2}    p2 = D(p, args)
;;   {:op :post :desc D :args A :din d :pin p :dout d2}  d2 = D.post(d, p, args)
;;   {:op :distance :desc D :args A :din d :pin p :dout d2}
;;   {:op :combine :desc D :args A :da :db :ma :mb :dout :mout}
;;   {:op :divide :k number :din :dout}              Lipschitz correction
;;   {:op :far :din d :bin b :dout d2}               d2 = max(d, b): the far field
;;                                                   (b a box's signed distance, a :prim)
;;   {:op :material :row r :mout m}                  a leaf's colour and mirror
;;   {:op :cells :desc D :args A :count n :pin :dout :mout :body [...] :cell-p p
;;    :body-d d :body-m m :near?}                    the nearest of n cells
;;   {... :near? {:p q :code [...] :bout b}}         ... the child in cell 0 (the
;;                                                   point's own) only; each other
;;                                                   cell's point in q, whose copy's
;;                                                   box distance `code` puts in b
;;   {:op :blend :desc D :args A :pin :dout :mout :count n :base b :stride s
;;    :members {:code [...] :d d :m m} :boxes [...] :grow r}
;;                                                   a union or smooth union of n
;;                                                   children of one structure: a loop
;;                                                   over their rows in the instance
;;                                                   bank (member j at b + j s), with
;;                                                   a grid (src/sdf/grid.fnl) the
;;                                                   plan gives it (:grid, :grid-data)
;; Each node's info: {:kind :path :class (:exact or :bound) :lipschitz k :bounds :far?
;; :even}.
;;
;; Strategies. How an object's code runs is a strategy of the tape object that holds
;; it; every emitter reads the same tape objects:
;;   - one object written out (its :code);
;;   - an instance group (:instances): many objects of one structure, one loop over
;;     their rows, with a grid (src/sdf/grid.fnl) when the plan gives it one;
;;   - a field (:field {:count :members :kinds :descs}): many small objects found
;;     through a uniform grid in float textures that the plan builds
;;     (src/render/field.fnl). The article's flat spheres and boxes are each the
;;     round-box primitive (a sphere of no extent, a box of no radius), met along a
;;     ray in closed form; any other bounded primitive placed by translations and
;;     rotations and coloured by :color alone is marched: its bounding sphere met in closed form,
;;     then its own distance sphere-traced in its frame (field-marched). It is the
;;     first object, so its members are numbered first.
;;
;; Repetitions. A :cells node evaluates its child in the point's own cell and the
;; neighbours (2 to 8 cells along the repeated axes, 2 around a polar one). Two
;; properties of the child cut that down (see :own-cell? and :boxed-neighbours? in
;; src/sdf/operations.fnl): a child even and never decreasing along the repeated
;; axes (:even, a box or a cylinder about the cell's centre) is nearest in its own
;; cell, so one cell is the same minimum; a costly child whose box keeps clear of its
;; cell's walls is evaluated in its own cell only, each neighbour's copy replaced by
;; its box's distance, a bound for it (never a hit, the box being a margin away).
;;
;; The far field. A node whose distance is divided by a Lipschitz factor (twist, bend,
;; displace) is a weak bound far from it: twist's and bend's factor grows with the
;; distance from their axis, so their value stays near 1/k however far the point is,
;; and a scene that is a min over such nodes never gives a step longer than that.
;; The signed distance to the node's bounding box is a bound too (what is inside the
;; box is no nearer than the box), so the node's value becomes the max of the two:
;; still a bound everywhere, and close to the true distance far away. Every object
;; also keeps its box's distance apart (:guard {:head n :bout b}: after its first n
;; instructions, register b holds it) and ends with the same max, so map() can skip
;; an object whose box is farther than the nearest distance found so far: its value,
;; at least the box's, could not lower the minimum. The skip changes no value, so
;; the CPU evaluator, which has no minimum to compare with, needs none.

;; `pairs` under another name: a loop over `pairs` by that name is LuaJIT's ITERN,
;; which Debian 12's LuaJIT ends early once despecialised (see src/util/wire.fnl).
(local each-pair pairs)

(local primitives (require :src.sdf.primitives))
(local operations (require :src.sdf.operations))
(local large-sphere (require :src.sdf.large-sphere))
(local custom (require :src.sdf.custom))
(local strategies (require :src.sdf.strategies))

(local sizes primitives.glsl-types)
(local box-desc (primitives.lookup :box))
(local translate-desc (operations.lookup :translate))

(local default-material [1 1 1 1])   ; white, a full mirror: the article's surfaces
;; The modern model's materials take two rows: colour and mirror amount, then
;; roughness and emission. Unset, a surface is matte white plastic.
(local modern-material [1 1 1 0 0.5 0 0 0])

(fn new-state [?modern? ?far-field? ?infos ?blends]
  ;; :blends: the blends of the `lower` under way, shared by every state it makes:
  ;; their children's rows (appended to the instance bank after the groups') and
  ;; their instructions (nil: no blends, as when folding).
  {:rows [] :relative [] :inner [] :derived [] :used {} :used-list [] :counter 0 :key []
   :blends ?blends
   ;; Point registers that are the shader's point translated only (a blend's grid
   ;; may then bound its children along a march's ray: see blend!).
   :translated {}
   :modern? ?modern? :far-field? (not= false ?far-field?) :infos (or ?infos {})})

(fn fresh! [st prefix]
  (set st.counter (+ st.counter 1))
  (.. prefix st.counter))

(fn use! [st name text]
  (when (not (. st.used name))
    (tset st.used name text)
    (table.insert st.used-list name)))

(fn alloc-args! [st desc vals]
  "Pack `vals` for `desc`'s :args into rows; returns arg references
{:row :offset :size :type}. An argument never straddles two rows. A float may take
the free end of the row the previous instruction left open (a sphere's radius beside
its translation); a vector starts a row of its own (a translation is always at
offset 0, where the camera is taken off it; see `hand-in`)."
  (let [refs []]
    (var row st.open-row)
    (var offset (if st.open-row st.open-offset 4))
    (var own? false)
    (var i 1)
    (each [_ a (ipairs desc.args)]
      (let [n (. sizes a.type)]
        (when (or (> (+ offset n) 4) (and (not own?) (> n 1)))
          (table.insert st.rows [0 0 0 0])
          (set row (- (length st.rows) 1))
          (set offset 0))
        (set own? true)
        (for [k 1 n]
          (tset (. st.rows (+ row 1)) (+ offset k) (. vals i))
          (set i (+ i 1)))
        (table.insert refs {: row : offset :size n :type a.type :estimate? a.estimate?})
        (when a.estimate? (set st.estimates? true))
        (set offset (+ offset n))))
    (assert (= (- i 1) (length vals))
            (.. (tostring desc.kind) ": packed " (length vals) " numbers for "
                (- i 1) " argument components"))
    (set st.open-row (when (< offset 4) row))
    (set st.open-offset offset)
    refs))

(fn material-row! [st material]
  (set st.open-row nil)
  (when (not= (. material 4) 1) (set st.mirrors? true))
  (table.insert st.rows [(. material 1) (. material 2) (. material 3) (. material 4)])
  (when st.modern?
    (table.insert st.rows [(. material 5) (. material 6) (. material 7) (. material 8)]))
  (- (length st.rows) (if st.modern? 2 1)))

(fn node-material [node inherited]
  (if (or node.color node.mirror node.roughness node.emission)
      (let [[r g b] (or node.color [(. inherited 1) (. inherited 2) (. inherited 3)])
            m (icollect [_ v (ipairs inherited)] v)]
        (tset m 1 r) (tset m 2 g) (tset m 3 b)
        (when (not= node.mirror nil) (tset m 4 node.mirror))
        (when (and (not= node.roughness nil) (. m 5)) (tset m 5 node.roughness))
        (when (and (not= node.emission nil) (. m 6)) (tset m 6 node.emission))
        m)
      inherited))

(fn symmetric-box [b]
  (when b {:lo (icollect [_ v (ipairs b)] (- v)) :hi b}))

(fn wrap-shorthand [node]
  "The node with its :scale, :rotate and :pos shorthands made explicit operations:
translate(rotate(scale(node)))."
  (var inner (collect [k v (each-pair node)]
               (when (and (not= k :pos) (not= k :rotate) (not= k :scale)) (values k v))))
  (when node.scale
    (set inner {:kind :scale :factor node.scale :children [inner] :path node.path
                :implicit? true}))
  (when node.rotate
    (set inner {:kind :rotate :angles node.rotate :angle 0 :children [inner] :path node.path
                :implicit? true}))
  (when node.pos
    (set inner {:kind :translate :offset node.pos :children [inner] :path node.path
                :implicit? true}))
  inner)

(var lower-node nil)

;; From this many children of one structure on, a union or a polynomial smooth union
;; lowers them to one loop (:blend) over their rows: a smooth union of 10,000 spheres
;; is then one sphere's code. The grid's threshold (src/sdf/grid.fnl), for the same
;; reason: a loop with a grid costs less than the children written out from there.
(local min-blend (. (require :src.sdf.grid) :min-members))

(fn lower-primitive [st code node desc pin material]
  ;; A primitive's form for particular values (a plane facing up), unless the tape
  ;; is for the interpreter (st.general?: general forms only).
  (let [desc (or (and desc.variant (not st.general?) (desc.variant node)) desc)
        dout (fresh! st "d")
        mout (fresh! st "m")]
    (use! st desc.glsl-name desc)
    (table.insert code {:op :prim :desc desc :args (alloc-args! st desc (desc.pack node))
                        : pin : dout})
    (table.insert code {:op :material :row (material-row! st material) : mout})
    (table.insert st.key desc.kind)
    {: dout : mout
     :info (let [bounds (and desc.bounds (desc.bounds node))]
             {:kind node.kind :path node.path :class desc.class :lipschitz desc.lipschitz
              :lipschitz-note desc.lipschitz-note : bounds :box (symmetric-box bounds) :children [] :even desc.even
              :symmetric (or desc.symmetric desc.even)
              :radius (when desc.bounding-radius (desc.bounding-radius node))
              ;; A custom node's function: written once for all its uses, at its
              ;; cost (the plan's budget of written nodes counts it).
              :custom (when node.custom {:key node.custom.key :cost node.custom.cost})})}))

(fn box-of [node desc info children]
  "The box {:lo :hi} holding `node` in its own frame, tighter than its symmetric
:bounds where the node is off-centre: the descriptor's :box-of when it has one (a
translation moves its child's box), a combination holds its children's boxes (grown
as the node's bounds grow beyond its children's). Never larger than the symmetric
bounds; nil when unbounded."
  (let [sym (symmetric-box info.bounds)
        boxes (icollect [_ c (ipairs children)] c.box)
        box (if (not sym) nil
                (and desc.box-of (= (length boxes) (length children))) (desc.box-of node boxes)
                (and (= desc.role :combine) (= (length boxes) (length children)))
                ;; The growth the node's bounds add to its children's (a blend radius).
                (let [grow (fcollect [i 1 3]
                             (math.max 0 (- (. info.bounds i)
                                            (accumulate [m 0 _ c (ipairs children)]
                                              (math.max m (. c.bounds i))))))]
                  {:lo (fcollect [i 1 3] (- (accumulate [m math.huge _ b (ipairs boxes)]
                                              (math.min m (. b.lo i)))
                                            (. grow i)))
                   :hi (fcollect [i 1 3] (+ (accumulate [m (- math.huge) _ b (ipairs boxes)]
                                              (math.max m (. b.hi i)))
                                            (. grow i)))})
                sym)]
    (when box
      {:lo (fcollect [i 1 3] (math.max (. box.lo i) (. sym.lo i)))
       :hi (fcollect [i 1 3] (math.min (. box.hi i) (. sym.hi i)))})))

(fn box-bound! [st code pin box ?centre?]
  "Append code putting into a new register the signed distance from point register
`pin` to `box` ({:lo :hi} about its origin), the point moved to the box's centre
first when `?centre?` (else the box is taken as centred); return the register."
  (let [bout (fresh! st "b")
        half (fcollect [i 1 3] (* 0.5 (- (. box.hi i) (. box.lo i))))
        centre (fcollect [i 1 3] (* 0.5 (+ (. box.hi i) (. box.lo i))))
        q (if ?centre?
              (let [q (fresh! st "p")]
                (use! st translate-desc.glsl-name translate-desc)
                (table.insert code {:op :point :desc translate-desc
                                    :args (alloc-args! st translate-desc centre) : pin :pout q})
                q)
              pin)]
    (use! st box-desc.glsl-name box-desc)
    (table.insert code {:op :prim :desc box-desc :args (alloc-args! st box-desc half)
                        :pin q :dout bout})
    bout))

(fn far-field! [st code din bin]
  (let [dout (fresh! st "d")]
    (table.insert code {:op :far : din : bin : dout})
    dout))

(fn correct-lipschitz! [st code k dout]
  ;; A field that changes k > 1 per unit is divided by k, so it never overshoots.
  (if (> k 1)
      (let [d2 (fresh! st "d")]
        (table.insert code {:op :divide : k :din dout :dout d2})
        d2)
      dout))

;; What lowering a child aside gives (its :info: bounds and far field), kept by node
;; for one `lower` (st.infos, shared with the aside states; values may change between
;; two lowerings, as functions of time do). Twist and bend need their child's before
;; they lower it for real; without this, nested twists lowered their innermost child
;; 2^depth times (14 deep: 0.19 s; 32 deep, the limit: days).
(fn child-info [st child]
  (when (= nil (. st.infos child))
    (tset st.infos child
          (. (lower-node (doto (new-state st.modern? st.far-field? st.infos st.blends)
                           (tset :aside? true) (tset :general? st.general?)) [] child "p0"
                         (if st.modern? modern-material default-material))
             :info)))
  (. st.infos child))

(fn min-context [node ?marks]
  "The paths of the nodes of object tree `node` whose value reaches the object's
through unions and point operations only (translations, rotations, mirrors: no
distance step after them), as a set: where a blend may stand (see blend!)."
  (let [marks (or ?marks {})
        desc (operations.lookup node.kind)]
    (tset marks node.path true)
    (when (and desc (= nil node.scale)
               (or (= desc.kind :union) (and (= desc.role :point) (= nil desc.post))))
      (each [_ c (ipairs (or node.children []))] (min-context c marks)))
    marks))

(fn blend-inside? [marks node]
  ;; Whether a node inside `node` will be a blend itself (a union or smooth union of
  ;; children enough, where a blend may stand).
  (accumulate [found? false _ c (ipairs (or node.children [])) &until found?]
    (or (and (. marks c.path) (or (= c.kind :union) (= c.kind :smooth-union))
             (>= (length (or c.children [])) min-blend))
        (blend-inside? marks c))))

(fn blend! [st code node desc form args-values pin material]
  "For a union or polynomial smooth union of at least min-blend children of one
structure (equal keys) that all have a box: append a :blend instruction to `code`
(one loop over the children's rows in the blend bank, see new-state's :blends) and return what
lowering the node gives ({:dout :mout :children :blend?}); else nil, and nothing is
changed."
  ;; Only where its value reaches the object's through unions and point operations
  ;; (st.min-context: a grid's lower bound for unlisted children then only shortens
  ;; steps); and not when a node inside will be a blend itself: its rows, lowered
  ;; aside, would not be laid out as the loop's body reads them.
  (when (and st.blends (not st.aside?) (. (or st.min-context {}) node.path)
             (>= (length node.children) min-blend)
             (or (= desc.kind :union)
                 (and (= desc.kind :smooth-union) (= form.glsl-name "opSmoothUnion")))
             (not (blend-inside? st.min-context node)))
    (let [aside (icollect [_ c (ipairs node.children)]
                  (let [cst (doto (new-state st.modern? st.far-field? st.infos st.blends) (tset :aside? true))
                        r (lower-node cst [] c "p0" material)]
                    {: cst :info r.info :key (table.concat cst.key " ")}))
          first (. aside 1)
          same? (accumulate [ok? true _ a (ipairs aside) &until (not ok?)]
                  (and (= a.key first.key) (not= nil a.info.box)
                       (= (length a.cst.rows) (length first.cst.rows))))]
      (when same?
        ;; The loop's body: the first child lowered again in this state's register
        ;; names (its rows from 0, read from the bank), reading the node's point.
        (let [bst (doto (new-state st.modern? st.far-field? st.infos st.blends) (tset :counter st.counter))
              body []
              r (lower-node bst body (. node.children 1) pin material)
              base (length st.blends.bank.rows)
              args (alloc-args! st desc args-values)
              dout (fresh! st "d")
              mout (fresh! st "m")]
          (set st.counter (math.max st.counter bst.counter))
          (set st.counter (+ st.counter 1))
          (each [_ name (ipairs bst.used-list)] (use! st name (. bst.used name)))
          (when bst.estimates? (set st.estimates? true))
          (use! st form.glsl-name form)
          (each [_ a (ipairs aside)]
            (when a.cst.mirrors? (set st.mirrors? true))
            (when a.cst.estimates? (set st.estimates? true))
            (each [_ row (ipairs a.cst.rows)] (table.insert st.blends.bank.rows row)))
          (let [ins {:op :blend :desc form : args : pin : dout : mout :count (length aside)
                     : base :stride (length first.cst.rows)
                     :members {:code body :d r.dout :m r.mout}
                     :boxes (icollect [_ a (ipairs aside)] a.info.box)
                     :grow (if (= desc.kind :smooth-union) node.radius 0)
                     ;; Whether a march may bound its unlisted children along the
                     ;; ray: lower-object says (only a blend that is its object's
                     ;; value, at the shader's point translated).
                     :along? false}]
            (table.insert code ins)
            (table.insert st.blends.list ins)
            ;; Numbered: objects holding blends are never one group (each blend
            ;; reads its own children's rows).
            (table.insert st.key (.. "blend#" (length st.blends.list) "[" first.key "]"))
            {: dout : mout :blend? true :children (icollect [_ a (ipairs aside)] a.info)}))))))

(fn symmetric-of [desc node children]
  "Along each axis, whether a node's distance and material are the same at -v as at v
(about its origin): see :keeps-symmetric in src/sdf/operations.fnl. A combination
reads only its children's distances."
  (fcollect [i 1 3]
    (if desc.symmetric-of (= true (desc.symmetric-of node children i))
        (let [keeps (or desc.keeps-symmetric desc.keeps-even (= desc.role :combine))]
          (and (not= nil keeps) (not= false keeps)
               (or (= true keeps) (= true (keeps node i)))
               (accumulate [ok? true _ c (ipairs children)]
                 (and ok? (= true (?. c :symmetric i)))))))))

(fn lower-operation [st code node desc pin material]
  (let [form (if st.general?
                 (operations.general desc node)
                 (operations.variant desc node (when desc.variant-reads-child?
                                                 (child-info st (. node.children 1)))))
        ;; A form packed its own way (a polar fold's lines).
        desc-args (if form.args form desc)
        _ (table.insert st.key (.. desc.kind (if node.kernel (.. "/" node.kernel) "")
                                   (if desc.variant-of (.. "/" form.glsl-name) "") "("))
        ;; Twist and bend pack their child's radius: lower the child once aside.
        args-values (if desc.needs-bounds
                        (let [child (child-info st (. node.children 1))
                              reason (.. ":" desc.kind " needs a child bounded in " desc.needs-bounds
                                         " (its Lipschitz factor grows with the child's size)")]
                          (when (not child.bounds)
                            (error {:lower-error (.. node.path ": " reason)
                                    : reason : node}))
                          (desc.pack node child))
                        (desc-args.pack node))
        result
        (case desc.role
          :point
          (let [pout (fresh! st "p")
                args (alloc-args! st desc-args args-values)
                _ (table.insert code {:op :point :desc form : args : pin : pout})
                _ (when (and (= desc.kind :translate) (or (= pin "p0") (. st.translated pin)))
                    (tset st.translated pout true))
                child (lower-node st code (. node.children 1) pout material)
                children [child.info]]
            (use! st form.glsl-name form)
            (var dout child.dout)
            (when desc.post
              (use! st desc.post.glsl-name desc.post)
              (let [d2 (fresh! st "d")]
                (table.insert code {:op :post :desc desc.post : args :din dout : pin :dout d2})
                (set dout d2)))
            {: dout :mout child.mout : children})
          :distance
          (let [child (lower-node st code (. node.children 1) pin material)
                dout (fresh! st "d")]
            (use! st form.glsl-name form)
            (table.insert code {:op :distance :desc form
                                :args (alloc-args! st desc-args args-values)
                                :din child.dout : pin : dout})
            {: dout :mout child.mout :children [child.info]})
          :combine
          (or (blend! st code node desc form args-values pin material)
              ;; Each child from the second on is folded in right after its code: its
              ;; distance and material die there (the interpreter's registers, see
              ;; src/sdf/interpret.fnl, stay few however many children there are).
              (let [args (alloc-args! st desc-args args-values)
                    lowered [(lower-node st code (. node.children 1) pin material)]]
                (use! st form.glsl-name form)
                (var (d m) (values (. lowered 1 :dout) (. lowered 1 :mout)))
                (for [i 2 (length node.children)]
                  (let [child (lower-node st code (. node.children i) pin material)
                        dout (fresh! st "d") mout (fresh! st "m")]
                    (table.insert lowered child)
                    (table.insert code {:op :combine :desc form : args
                                        :da d :db child.dout
                                        :ma m :mb child.mout : dout : mout})
                    (set (d m) (values dout mout))))
                {:dout d :mout m :children (icollect [_ c (ipairs lowered)] c.info)}))
          :cells
          (let [args (alloc-args! st desc-args args-values)
                cell-p (fresh! st "p")
                body []
                child (lower-node st body (. node.children 1) cell-p material)
                own? (and desc.own-cell? (desc.own-cell? node child.info))
                count (if own? 1 (desc.cells node))
                near (when (and (not own?) (> count 1) desc.boxed-neighbours?
                                (desc.boxed-neighbours? node child.info))
                       (let [q (fresh! st "p")
                             box-code []
                             bout (box-bound! st box-code q child.info.box true)]
                         {:p q :code box-code : bout}))
                dout (fresh! st "d") mout (fresh! st "m")]
            (use! st form.glsl-name form)
            (table.insert st.key (.. "x" count (if near "near" "")))
            (table.insert code {:op :cells :desc form : args : count : pin : dout : mout
                                : body : cell-p :body-d child.dout :body-m child.mout
                                :near? near})
            {: dout : mout :children [child.info] :near? (not= nil near)}))
        info {:kind node.kind :path node.path :implicit? node.implicit?
              :children result.children :blend? result.blend?}]
    ;; Neighbours drawn by their boxes give a bound, not the distance.
    (set info.class (if result.near? :bound (desc.class-of node result.children)))
    (set info.even (when desc.keeps-even
                     (fcollect [i 1 3]
                       (and (accumulate [ok? true _ c (ipairs result.children)]
                              (and ok? (= true (?. c :even i))))
                            (or (= true desc.keeps-even) (desc.keeps-even node i))))))
    (set info.symmetric (symmetric-of desc node result.children))
    (set info.bounds (desc.bounds-of node result.children))
    (set info.lipschitz (if desc.lipschitz-of (desc.lipschitz-of node result.children) 1))
    (set info.box (box-of node desc info result.children))
    (table.insert st.key ")")
    (let [dout (if desc.corrects? result.dout
                   (correct-lipschitz! st code info.lipschitz result.dout))]
      ;; Whether a node can divide is its kind's, not its values' (a factor of 1 now
      ;; may be more after a value edit): the code's shape stays a function of the key.
      (if (and desc.lipschitz-of info.bounds st.far-field?)
          (do (set info.far? true)
              (table.insert st.key "far")
              {:dout (far-field! st code dout (box-bound! st code pin (symmetric-box info.bounds)))
               :mout result.mout : info})
          {: dout :mout result.mout : info}))))

(set lower-node
     (fn [st code node pin inherited]
       (let [material (node-material node inherited)
             node (wrap-shorthand node)]
         ;; A custom node's descriptor comes from its own data (src/sdf/custom.fnl).
         (case (or (custom.descriptor node) (primitives.lookup node.kind))
           desc (lower-primitive st code node desc pin material)
           _ (lower-operation st code node (assert (operations.lookup node.kind)
                                                   (.. "unknown kind " (tostring node.kind)))
                              pin material)))))

(fn each-instruction [code f]
  "Call `f` on every instruction of `code`, in order, each before those nested in it
(a repetition's :body, a near repetition's neighbours' :code): the one walk of a
tape that the lowering's passes share."
  (each [_ ins (ipairs code)]
    (f ins)
    (when ins.body (each-instruction ins.body f))
    (when ins.near? (each-instruction ins.near?.code f))))

;; An object's translation T is sent as T - camera, so its point is the camera-relative
;; one moved to the object's origin. When that origin is far from what the object draws
;; (a plane, unbounded; an object without a placement, whose origin is the world's),
;; that point is the world point, rounded to float32 (0.0625 apart at 1e6): rings and
;; lost shadows. When every instruction reading the translation's output is a
;; translation (a child's :pos, the guard's box centre) or a plane, the camera is taken
;; off one level in instead: T is sent as 0, each such translation t as T + t - camera
;; and each such plane's height h as h + dot(n, T - camera), in double. The code is the
;; same; the CPU evaluator reads the rows in world coordinates. lower-object does it
;; for an object without a placement, and for a placed one when only planes read its
;; point (a placed group keeps its children's offsets constant, for folding).
(fn hand-in [code]
  "{:translations [row ...] :planes [{:row r :height ref} ...]} for the instructions of
`code` that read the object's translation's output (its first instruction), when each
is a translation or a plane; else nil."
  (let [p (. code 1 :pout)
        found {:translations [] :planes []}]
    (var ok? (= :point (?. code 1 :op)))
    (when ok?
      (each-instruction
       (icollect [i ins (ipairs code)] (when (> i 1) ins))
       (fn [ins]
         (when (= ins.pin p)
           (case [ins.op (?. ins :desc :kind)]
             [:point :translate] (table.insert found.translations (. ins.args 1 :row))
             [:prim :plane] (let [[n h] ins.args]
                              ;; The normal and the height share one row.
                              (assert (and (= n.row h.row) (= n.offset 0) (= h.offset 3)))
                              (table.insert found.planes {:row n.row :height h}))
             ;; The ground form's one vec4 is the same row.
             [:prim :ground] (let [[nh] ins.args]
                               (table.insert found.planes {:row nh.row :height nh}))
             _ (set ok? false))))))
    (when (and ok? (or (> (length found.translations) 0) (> (length found.planes) 0)))
      found)))

(fn lower-object [st node]
  ;; The shader's point is camera-relative. The object's outermost translation takes
  ;; the camera position off in double on the CPU (its row is marked relative); an
  ;; object without one gets a translation by zero, whose point would be the world
  ;; point: the camera is taken off one level in where it can be (see hand-in).
  (let [wrapped (wrap-shorthand node)
        unplaced? (not= wrapped.kind :translate)
        top (if unplaced?
                {:kind :translate :offset [0 0 0] :children [wrapped] :path node.path
                 :implicit? true}
                wrapped)
        code []
        before (length st.rows)
        _ (set st.min-context (min-context node))
        result (lower-node st code top "p0" (if st.modern? modern-material default-material))
        ;; The placed node's bounds are about the translation's output point, which
        ;; the first instruction computes: the guard's box goes right after it.
        placed (. result.info.children 1)
        n (length code)
        ;; A placed node with a far field of its own (a twist with :pos) already
        ;; ends with its box's max on that point: its box becomes the guard's.
        own? (and placed placed.far? (= :far (?. code n :op))
                  (= (?. code (- n 1) :pin) (?. code 1 :pout)))
        ;; An exact primitive gets no guard: its own distance costs about what its
        ;; box's does, and is never below it, so the max would change nothing. An
        ;; operation's guard skips a subtree; a bound primitive's (an ellipsoid, a
        ;; custom node) also lifts its weak bound far away to the box's.
        guard (when (and placed placed.box
                         (or (> (length placed.children) 0) (not= placed.class :exact))
                         (= :point (?. code 1 :op)) st.far-field?)
                (table.insert st.key "guard")
                (if own?
                    (let [box (table.remove code (- n 1))]
                      (table.insert code 2 box)
                      {:head 2 :bout box.dout})
                    ;; The placed node's box may be off its origin (a tower standing
                    ;; on z = 0): the guard's box is moved to its centre.
                    (let [tail []
                          bout (box-bound! st tail (. code 1 :pout) placed.box true)]
                      (for [i (length tail) 1 -1] (table.insert code 2 (. tail i)))
                      {:head (+ 1 (length tail)) : bout})))
        dout (if (and guard (not own?)) (far-field! st code result.dout guard.bout)
                 result.dout)]
    ;; Which blends may be pruned (src/sdf/grid.fnl stands a lower bound in for a
    ;; cell's unlisted children): those whose value reaches the object's through
    ;; unions (min), far fields (max with a box) and Lipschitz divisions only. There a
    ;; lower bound only shortens steps; under a smooth union, a round or any other
    ;; operation it could move the surface (a smooth union of a bound bulges out).
    ;; Such a blend whose value is the object's, at the shader's point translated,
    ;; also bounds its unlisted children along a march's ray (:along?): a step that
    ;; no child's surface is met within is one no surface of the object is met within.
    (let [safe {result.dout true dout true}]
      (for [i (length code) 1 -1]
        (let [ins (. code i)]
          (when (. safe ins.dout)
            (case ins.op
              :far (tset safe ins.din true)
              :divide (tset safe ins.din true)
              (where :combine (= ins.desc.glsl-name "opUnion"))
              (do (tset safe ins.da true) (tset safe ins.db true))
              :blend (do (set ins.prunable? true)
                         (set ins.along? (and (= ins.dout result.dout)
                                              (or (= ins.pin "p0")
                                                  (= true (. st.translated ins.pin)))))))))))
    ;; The translate's arguments are the first row this object allocated.
    (table.insert st.relative before)
    (case (hand-in code)
      (where inner (or unplaced? (= 0 (length inner.translations))))
      (do (table.insert st.inner (doto inner (tset :root before)))
          ;; An unplaced object's translation by zero is then the identity: its
          ;; readers read the shader's point itself.
          (when unplaced?
            (let [p (. (table.remove code 1) :pout)]
              (each-instruction code #(when (= $.pin p) (set $.pin "p0")))
              (when guard (set guard.head (- guard.head 1)))
              (table.insert st.key "identity")))))
    (table.insert st.key ";")
    {:index node.index : code : dout :mout result.mout :info result.info : guard}))

(fn lower-large-sphere [st node]
  ;; A sphere of radius 1000 or more, placed by :pos: its cancellation-free form (see
  ;; src/sdf/large-sphere.fnl) on the camera-relative point itself. Its first row
  ;; (centre, radius) is made camera-relative on upload, its second (k) derived.
  (let [desc large-sphere.descriptor
        [x y z] (or node.pos [0 0 0])
        r node.radius
        dout (fresh! st "d")
        mout (fresh! st "m")
        args (alloc-args! st desc [x y z r 0])
        code [{:op :prim : desc : args :pin "p0" : dout}
              {:op :material :row (material-row! st (node-material node (if st.modern? modern-material
                                                                             default-material)))
               : mout}]]
    (use! st desc.glsl-name desc)
    (table.insert st.relative (. args 1 :row))
    ;; (Its material row closed the derived row: nothing else shares it.)
    (table.insert st.derived {:row (. args 2 :row) :centre (. args 1 :row)})
    (table.insert st.key "large-sphere;")
    {:index node.index : code : dout : mout
     :info {:kind :sphere :path node.path :class :exact :lipschitz 1 :bounds [r r r] :radius r
            :box (symmetric-box [r r r]) :children [] :large? true}}))

(fn leaf-of [code dout]
  "{:points [translations] :prim instruction} when `code` is translations and then one
primitive whose distance is the object's (`dout`), else nil: the object's exact
normal is then its primitive's gradient at the translated point, and a half-space is
met in closed form."
  (let [points []]
    (var prim nil)
    (var ok? true)
    (each [_ ins (ipairs code)]
      (case ins.op
        :point (if (and (not prim) (= ins.desc.kind :translate)) (table.insert points ins)
                   (set ok? false))
        :prim (if prim (set ok? false) (set prim ins))
        :material nil
        _ (set ok? false)))
    (when (and ok? prim (= prim.dout dout))
      {: points : prim})))
(fn fold! [st objects]
  "Give every argument and material of `objects`' code that does not sit in a
camera-relative row (nor takes the camera off, see hand-in) its numbers as :literal,
and the key those numbers: the GLSL emitter then writes them as constants (see the
tape's :fold? in `lower`)."
  (let [relative (collect [_ r (ipairs st.relative)] r true)
        ;; Derived rows (a large sphere's k) follow the camera too.
        _ (each [_ dv (ipairs st.derived)] (tset relative dv.row true))
        ;; Rows that take the camera off one level in (see hand-in) stay uniforms; of
        ;; a plane's row only the height does (its normal is folded).
        heights {}
        plane-rows {}
        _ (each [_ inner (ipairs st.inner)]
            (each [_ r (ipairs inner.translations)] (tset relative r true))
            (each [_ pl (ipairs inner.planes)]
              (tset heights pl.height true)
              (tset plane-rows pl.row true)))
        row-values (fn [row n] (fcollect [k 1 n] (. st.rows (+ row 1 (math.floor (/ (- k 1) 4)))
                                                     (+ 1 (% (- k 1) 4)))))]
    (each [_ o (ipairs objects)]
      (each-instruction o.code
                        (fn [ins]
                          (each [_ ref (ipairs (or ins.args []))]
                            (when (not (or (. relative ref.row) (. heights ref)))
                              (set ref.literal (fcollect [k 1 ref.size]
                                                 (. st.rows (+ ref.row 1) (+ ref.offset k))))))
                          (when (= ins.op :material)
                            (set ins.literal (row-values ins.row (if st.modern? 8 4)))))))
    ;; The values are part of the code now: they are part of its key.
    (table.insert st.key "fold:")
    (each [i row (ipairs st.rows)]
      (when (not (. relative (- i 1)))
        (let [folded (if (. plane-rows (- i 1)) [(. row 1) (. row 2) (. row 3)] row)]
          (table.insert st.key (table.concat (icollect [_ v (ipairs folded)] (string.format "%.9g" v))
                                             ",")))))))

;;; The field strategy.

(local round-box-desc (primitives.lookup :round-box))
(local rotate-desc (operations.lookup :rotate))

;; A marched field member's packed numbers, at most: two texels of the field's
;; objects texture (shaders/pipeline/field-primitives.glsl's fieldMarchedFrame).
(local max-marched-args 8)

(local marched-keys {:kind true :path true :path-list true :index true :pos true
                     :rotate true :color true})

(fn marched-chain [node]
  ;; `node` as a marched field member sees it (see field-marched): down its chain of
  ;; placements (translations and rotations, written as operations of one child or
  ;; as :pos and :rotate) to one primitive: that leaf, the rows m of the rotation
  ;; and the origin c (world) with the leaf's point m (p - c), and the innermost
  ;; colour; nil when anything else is on the way (a scale, a material, another
  ;; operation).
  (var (m c color leaf) (values [1 0 0 0 1 0 0 0 1] [0 0 0] nil nil))
  (var at node)
  (var ok? true)
  (fn translate! [[ox oy oz]]
    ;; p - o in the current frame: c moves by m's transpose times o.
    (let [[a b c3 d e f g h k] m
          [cx cy cz] c]
      (set c [(+ cx (* a ox) (* d oy) (* g oz)) (+ cy (* b ox) (* e oy) (* h oz))
              (+ cz (* c3 ox) (* f oy) (* k oz))])))
  (fn rotate! [r]
    ;; Its rows times the current frame's.
    (set m (fcollect [i 0 8]
             (let [row (math.floor (/ i 3)) col (% i 3)]
               (+ (* (. r (+ (* 3 row) 1)) (. m (+ col 1)))
                  (* (. r (+ (* 3 row) 2)) (. m (+ col 4)))
                  (* (. r (+ (* 3 row) 3)) (. m (+ col 7))))))))
  (while (and ok? (not leaf))
    (let [op (and (. {:translate true :rotate true} at.kind) (operations.lookup at.kind))
          desc (and (not op) (primitives.lookup at.kind))
          own (collect [_ p (ipairs (or (?. op :params) (?. desc :params) []))] p.name true)]
      (each [k (each-pair at)]
        (when (not (or (. marched-keys k) (. own k) (and op (= k :children))))
          (set ok? false)))
      (when at.color (set color at.color))
      ;; The shorthands as wrap-shorthand makes them: translate(rotate(node)).
      (when at.pos (translate! at.pos))
      (when at.rotate (rotate! (rotate-desc.pack {:angles at.rotate :angle 0})))
      (if (not ok?) nil
          (and op (= 1 (length at.children)))
          (do (if (= at.kind :translate) (translate! at.offset) (rotate! (rotate-desc.pack at)))
              (set at (. at.children 1)))
          desc (set leaf at)
          (set ok? false))))
  (when (and ok? leaf)
    (values leaf m c color)))

(fn field-marched [o]
  "Scene object `o` as a marched field member, or nil when it is not one: one
primitive placed by translations and rotations alone (:pos, :rotate, or those
operations of one child), coloured by :color alone (its material the default, as a
flat sphere's), bounded, of Lipschitz factor 1 and at most max-marched-args
numbers. Returns {:desc :args (its packed numbers) :rows (the rotation into its
frame, 9 numbers, rows first) :centre (its origin, world) :color :radius (its
bounding sphere's, about its origin)}."
  (let [(leaf rows centre color) (when o.tree (marched-chain o.tree))
        desc (when leaf (primitives.lookup leaf.kind))]
    (when (and desc (not desc.half-space?) desc.bounds
               (not (and desc.variant (desc.variant leaf)))
               (= 1 (or desc.lipschitz 1)))
      (let [bounds (desc.bounds leaf)
            args (desc.pack leaf)]
        (when (and bounds (<= (length args) max-marched-args))
          (let [[hx hy hz] bounds]
            {: desc : args : rows : centre :color (or color [1 1 1])
             :radius (math.sqrt (+ (* hx hx) (* hy hy) (* hz hz)))}))))))

(fn field-shape [o]
  "Field member `o` as the field's round box about its centre: cx cy cz (world), half
extents hx hy hz, radius r. The article's flat sphere or box is that primitive
exactly; a marched member (field-marched) is its bounding sphere."
  (if o.tree
      (let [{:centre [x y z] : radius} (field-marched o)]
        (values x y z 0 0 0 radius))
      (let [[x y z] o.pos]
        (if (= o.kind :sphere)
            (values x y z 0 0 0 o.radius)
            (let [[sx sy sz] o.size]
              (values x y z (* 0.5 sx) (* 0.5 sy) (* 0.5 sz) 0))))))

(fn field-kinds [members]
  "Which kinds the field members `members` hold: {:spheres? :boxes? :marched (the
marched members' kinds, in order of first appearance: a member's kind number is its
place there)}. Only their code is compiled in."
  (let [kinds {:spheres? false :boxes? false :marched []}
        seen {}]
    (each [_ o (ipairs members)]
      (if o.tree
          (let [kind (. (field-marched o) :desc :kind)]
            (when (not (. seen kind))
              (tset seen kind true)
              (table.insert kinds.marched kind)))
          (tset kinds (if (= o.kind :sphere) :spheres? :boxes?) true)))
    kinds))

(fn field-object [members]
  ;; The field's tape object for `members` (see Strategies above): no code of its
  ;; own; its members themselves (each one's round box is field-shape's, made where
  ;; it is needed: a million spheres keep no second copy). Its kinds: whether it
  ;; holds spheres, boxes, and which primitives are marched (:marched, in order of
  ;; first appearance: a member's kind number is its place there); :descs, the
  ;; primitives whose GLSL it calls.
  (let [kinds (field-kinds members)]
    {:strategy :field
     :field {:count (length members) : kinds
             : members
             :desc round-box-desc
             :descs (doto (icollect [_ k (ipairs kinds.marched)] (primitives.lookup k))
                      (table.insert 1 round-box-desc))}
     :indices (icollect [_ o (ipairs members)] o.index)
     :id 0
     :info {:kind "field" :field? true :path (.. "objects[" (. members 1 :index) "]")
            :class (if (accumulate [bound? false _ k (ipairs kinds.marched)]
                         (or bound? (= :bound (. (primitives.lookup k) :class))))
                       :bound :exact)
            :lipschitz 1 :children [] :implicit? false}}))

(fn node-of [o]
  "The scene-tree node that draws scene object `o` (with its :index): its tree, or
for one of the article's flat objects (a sphere, box or plane written with only its
own fields) the same leaf as a node, placed by :pos and coloured by :color."
  (if o.tree
      (doto (collect [k v (each-pair o.tree)] k v) (tset :index o.index))
      (let [node (collect [k v (each-pair o)] k v)]
        (set node.path (.. "objects[" o.index "]"))
        (when (= o.kind :plane) (set node.normal [0 0 1]))
        node)))

;; From this many objects of one structure on (equal keys: the same code but for their
;; values), they are drawn as one instance group, a loop over their rows. Fewer are
;; written out one by one, as a person would by hand: the driver then has no loop to
;; unroll (llvmpipe leaves some unrolled).
(local min-group 9)

(fn strategy-for [count]
  ;; The drawing strategy of `count` objects of one structure (equal keys): the first
  ;; by :rank (the lowest) whose :takes? accepts the count, of those that lowering
  ;; chooses (src/sdf/strategies.fnl).
  (accumulate [found nil _ s (ipairs (strategies.chosen-in-lowering)) &until found]
    (when (s.takes? count) s)))

(fn relocate! [code offset seen]
  ;; Every row `code` reads, `offset` further on (a :post shares its :point's args).
  (each-instruction code
                    (fn [ins]
                      (each [_ ref (ipairs (or ins.args []))]
                        (when (not (. seen ref))
                          (tset seen ref true)
                          (set ref.row (+ ref.row offset))))
                      (when (= ins.op :material) (set ins.row (+ ins.row offset))))))

(fn new-bank [] {:rows [] :relative [] :inner [] :derived []})

(fn append-rows! [bank ost]
  ;; The rows of object state `ost`, and what its rows are (relative, handed in,
  ;; derived), appended to `bank`; returns the offset they got.
  (let [offset (length bank.rows)
        at #(+ $ offset)]
    (each [_ row (ipairs ost.rows)] (table.insert bank.rows row))
    (each [_ r (ipairs ost.relative)] (table.insert bank.relative (at r)))
    (each [_ {: root : translations : planes} (ipairs ost.inner)]
      (table.insert bank.inner {:root (at root)
                                :translations (icollect [_ r (ipairs translations)] (at r))
                                :planes (icollect [_ pl (ipairs planes)]
                                          {:row (at pl.row) :height pl.height})}))
    (each [_ dv (ipairs ost.derived)]
      (table.insert bank.derived {:row (at dv.row) :centre (at dv.centre)}))
    offset))

(fn lower-one [options infos node blends]
  ;; Object `node` lowered alone: its state (rows from 0) and its tape object.
  (let [st (doto (new-state options.modern? options.far-field? infos blends)
             (tset :general? options.general-forms?))
        large? (and (large-sphere.large? node) (= nil node.scale))
        o (if large? (lower-large-sphere st node) (lower-object st node))]
    (set o.leaf (leaf-of o.code o.dout))
    (set o.size (length st.rows))
    (set o.half-space? (= true (?. o :leaf :prim :desc :half-space?)))
    (values st o)))

(fn lower [objects ?options]
  "Lower the validated tree objects `objects` (each a node with :index, its scene
index, and :path; see node-of) into a tape (see the top of this file), or nil and a
message naming the node when a node cannot be lowered (a twist of an unbounded
child), then that node and the reason alone. Option :modern? gives every material two
rows (:material-size 8); :general-forms? lowers each operation and primitive to its
general form (operations.general: the tape interpreter's); :far-field? false leaves out far fields and guards (the
benchmark's before); :fold? true writes every value but the camera-relative rows (and
those of `hand-in`) into the code as constants (:literal on arguments and materials),
and into the key; an instance group's values stay in its bank. Option :field, a list
of the article's flat spheres and boxes (scene objects, not in `objects`), draws them
as a field: the first tape object (see Strategies above)."
  (let [blends {:bank (new-bank) :list []}
        options (or ?options {})
        field (when (and options.field (> (length options.field) 0)) (field-object options.field))
        infos {}
        (ok? lowered) (pcall #(icollect [_ node (ipairs objects)]
                                (let [(st o) (lower-one options infos node blends)]
                                  {: st : o :key (table.concat st.key " ")})))]
    (if (not ok?)
        (if (and (= (type lowered) :table) lowered.lower-error)
            (values nil lowered.lower-error lowered.node lowered.reason)
            (error lowered 0))
        (let [counts {}
              _ (each [_ l (ipairs lowered)] (tset counts l.key (+ 1 (or (. counts l.key) 0))))
              tape-bank (new-bank)
              group-bank (new-bank)
              groups {}
              group-order []
              out []
              used {}
              used-list []
              key []]
          (var mirrors? false)
          (var estimates? false)
          (var id 0)
          (when field
            (table.insert out field)
            (set id field.field.count)
            (table.insert key (.. "field:" id (if field.field.kinds.spheres? "s" "")
                                  (if field.field.kinds.boxes? "b" "")
                                  (table.concat (icollect [_ k (ipairs field.field.kinds.marched)]
                                                  (.. "," k))))))
          (each [_ {: st : o :key k} (ipairs lowered)]
            (when st.mirrors? (set mirrors? true))
            (when st.estimates? (set estimates? true))
            (each [_ name (ipairs st.used-list)]
              (when (not (. used name))
                (tset used name (. st.used name))
                (table.insert used-list name)))
            ;; The strategy that draws the objects of this structure: one tape
            ;; object each, their rows in the tape's bank, or gathered into one
            ;; whose members' rows go one after another in the instance bank.
            (let [s (strategy-for (. counts k))]
              (if (not s.gathers?)
                  (do (relocate! o.code (append-rows! tape-bank st) {})
                      (set (o.id o.strategy) (values id s.name))
                      (set id (+ id 1))
                      (table.insert out o)
                      (table.insert key (s.key k 1)))
                  (. groups k)
                  (let [g (. groups k)]
                    (table.insert g.states st)
                    (table.insert g.o.indices o.index)
                    (table.insert g.o.infos o.info))
                  (do (set o.indices [o.index])
                      (set o.infos [o.info])
                      (set (o.id o.strategy) (values id s.name))
                      (set id (+ id (. counts k)))
                      (tset groups k {: o :states [st]})
                      (table.insert group-order (. groups k))
                      (table.insert out o)
                      (table.insert key (s.key k (. counts k)))))))
          ;; A group's members' rows one after another (at base + member * stride),
          ;; groups in order.
          (each [_ {: o : states} (ipairs group-order)]
            (let [base (append-rows! group-bank (. states 1))]
              (for [m 2 (length states)] (append-rows! group-bank (. states m)))
              (set o.instances {:count (length states) : base
                                :stride (length (. states 1 :rows))})))
          ;; The blends' children's rows after the groups' (see blend!).
          (let [offset (append-rows! group-bank blends.bank)]
            (each [_ ins (ipairs blends.list)] (set ins.base (+ ins.base offset))))
          (let [st (doto (new-state options.modern?)
                     (tset :rows tape-bank.rows) (tset :relative tape-bank.relative)
                     (tset :inner tape-bank.inner) (tset :derived tape-bank.derived)
                     (tset :key key))]
            (when options.fold?
              (fold! st (icollect [_ o (ipairs out)] (when (. (strategies.of o) :folds?) o))))
            (table.insert key (.. "rows:" (length tape-bank.rows)))
            (when options.modern? (table.insert key "materials:8"))
            {:objects out :count id :rows tape-bank.rows :relative tape-bank.relative
             :inner tape-bank.inner :derived tape-bank.derived :instances group-bank
             :blends blends.list
             : mirrors? : estimates?
             :material-size (if options.modern? 8 4)
             :used (icollect [_ name (ipairs used-list)] {: name :desc (. used name)})
             :key (table.concat key " ")})))))

(fn may-refuse? [node]
  "Whether lowering scene-tree `node` can refuse it (`lower` returning nil and a
message): only a node whose operation needs a bounded child (twist, bend: the
descriptor's :needs-bounds) or a custom node (its data is checked), anywhere in the
tree, can. The loader lowers those alone to report the refusal at the node's line,
and leaves the others to the plan's one lowering."
  (let [desc (operations.lookup node.kind)]
    (or (= node.kind :custom) (not= nil (?. desc :needs-bounds))
        (accumulate [found? false _ c (ipairs (or node.children [])) &until found?]
          (may-refuse? c)))))

(fn infos-by-index [tape]
  "Each object's lowered root info by its scene index (an instance group's members'
each)."
  (let [out {}]
    (each [_ o (ipairs tape.objects)]
      ;; (A field's members have no lowered tree.)
      (case ((. (strategies.of o) :infos) o)
        infos (each [m index (ipairs (or o.indices [o.index]))]
                (tset out index (. infos m)))))
    out))

(fn class-label [info]
  (.. (if info.lipschitz-note
          (string.format "bound, Lipschitz %.3g (%s)" info.lipschitz info.lipschitz-note)
          (> info.lipschitz 1)
          (string.format "bound, Lipschitz %.3g (steps divided by it)" info.lipschitz)
          (= info.class :exact) "exact"
          "bound")
      (if info.far? ", far field from its box" "")))

(fn describe [tape]
  "Lines describing every node of `tape`'s objects, indented by depth, with its class:
what `--tree` prints."
  (let [lines []]
    (fn walk [info depth ?more]
      (let [b info.bounds
            bounds (if b (string.format "bounds ±%.3g ±%.3g ±%.3g" (. b 1) (. b 2) (. b 3))
                       info.field? "each member's box"
                       "unbounded")]
        (table.insert lines (.. (string.rep "  " depth) info.kind
                                (if info.implicit? " (shorthand)" "")
                                (or ?more "")
                                "  " (class-label info) "  " bounds "  " info.path)))
      (each [_ c (ipairs info.children)] (walk c (+ depth 1))))
    (each [_ o (ipairs tape.objects)] (walk o.info 0 ((. (strategies.of o) :describe) o)))
    lines))

{: lower : describe : node-of : min-group : infos-by-index : field-shape : field-marched : field-kinds
 : may-refuse?}
