;; The operation catalogue: transforms, combinations and domain operations, one
;; descriptor file each in src/sdf/operations/, found by listing that folder as the
;; primitives are (src/sdf/primitives.fnl): adding an operation is adding one file
;; (what several share is in src/sdf/operation-kit.fnl).
;; Every descriptor has :kind :doc :params :role, its GLSL text and name, its CPU form,
;; and says how it changes the exactness, the Lipschitz factor and the bounds of its
;; children. Roles:
;;   :point    one child; maps the point before the child:  vec3 opX(vec3 p, args)
;;             / (fn [x y z ...]) -> x y z; optional :post distance step after it
;;   :distance one child; changes its distance:  float opX(float d, vec3 p, args)
;;             / (fn [d x y z ...]) -> d
;;   :combine  two or more children, folded left:  float opX(float a, float b, args)
;;             / (fn [a b ...]) -> d; and a material weight of the first operand,
;;             float wX(float a, float b, args) / :cpu-weight (fn [a b ...]) -> w
;;   :cells    one child evaluated in several cells (repetition), the nearest kept:
;;             vec3 opX(vec3 p, args, int cell) / (fn [cell x y z ...]) -> x y z
;; :class-doc says it in words for `--kinds`.
;; :class-of (fn [o children]) -> :exact or :bound, where children are the lowered
;; children's infos ({:class :bounds}); :lipschitz-of (fn [o children]) -> k >= 1 (the
;; lowering divides the distance by k, unless the :post step corrects it point by
;; point: :corrects? true, as twist and bend do); optional :box-of (fn [o child-boxes]) ->
;; {:lo :hi}, a box tighter than the symmetric bounds (see box-of in src/sdf/lower.fnl);
;; :bounds-of (fn [o children]) -> half extents
;; or nil (unbounded).
;; A :cells node may say how few cells need the child itself (see src/sdf/lower.fnl):
;; :own-cell? (fn [o child]) true when the point's own cell always holds the nearest
;; copy; :boxed-neighbours? (fn [o child]) true when a copy's box, in the neighbour
;; cells, is a bound good enough to take the copy's place there. `child`: the
;; lowered child's info ({:even :box :children}).
;; :keeps-even: true, or (fn [o axis]) -> boolean, when the node's distance is even
;; and never decreasing along that axis wherever its children's are (see a
;; primitive's :even in src/sdf/primitives.fnl): min and max of such functions, and
;; moves that leave that coordinate alone, are too.
;; :keeps-symmetric: true, or (fn [o axis]) -> boolean, when the node's distance and
;; material are the same at -v as at v along that axis (about its origin) wherever
;; its children's are: :symmetric in a lowered node's info (a primitive's :symmetric
;; or :even). Functions of the children's distances (unions, subtractions, smooth
;; blends, round, onion) and point maps that commute with the reflection keep it; a
;; :keeps-even node keeps it too. :symmetric-of (fn [o children axis]) -> boolean
;; instead, for a node symmetric whatever its children (a mirror across that axis).

(local files (require :src.util.files))

(local dir "src/sdf/operations")

(local roles {:point true :distance true :combine true :cells true})

(fn check-descriptor [d file]
  (fn need [ok? what] (assert ok? (.. file ": operation " what)))
  (need (= (type d) :table) "must be a table")
  (need (and (= (type d.kind) :string) (d.kind:match "^[a-z][a-z0-9%-]*$")) "needs a :kind name")
  (need (= (.. d.kind ".fnl") (file:match "[^/]*$")) "needs its :kind as its file's name")
  (need (. roles d.role) "needs a :role: point, distance, combine or cells")
  (need (= (type d.doc) :string) "needs :doc")
  (need (= (type d.class-doc) :string) "needs :class-doc")
  (need (= (type d.params) :table) "needs :params")
  (need (and (= (type d.args) :table) (= (type d.pack) :function)) "needs :args and :pack")
  (need (or (= (type d.variants) :table)
            (and (= (type d.glsl-name) :string) (= (type d.glsl) :string) (= (type d.cpu) :function)))
        "needs :glsl-name, :glsl and :cpu (or :variants of them)")
  (need (= (type d.class-of) :function) "needs :class-of")
  (need (= (type d.bounds-of) :function) "needs :bounds-of")
  d)

(local operations
  (icollect [_ name (ipairs (assert (files.list-project dir)))]
    (let [base (name:match "^(.-)%.fnl$")]
      (when base
        (check-descriptor (require (.. "src.sdf.operations." base)) (.. dir "/" name))))))

(local by-kind (collect [_ d (ipairs operations)] d.kind d))

(fn variant [d o ?child]
  "The GLSL and CPU forms of operation `d` for node `o` (kernel variants; a
repetition's for the axes it repeats along; a polar one's for its child, whose
lowered info `?child` is when `d` has :variant-reads-child?). A form with its own
:args and :pack is packed by them."
  (if d.variants (. d.variants (or o.kernel :poly))
      d.variant-of (or (d.variant-of o ?child) d)
      d))

(fn general [d o]
  "The form of operation `d` for node `o` that holds whatever its values: its kernel's
(:variants), never one made for particular values (:variant-of: a repetition along
some axes, a rotation that permutes them, a polar fold of a symmetric child). The
tape interpreter's (one shader for every scene): the same values, so the same
distances."
  (if d.variants (. d.variants (or o.kernel :poly)) d))

(fn lookup [kind]
  "The descriptor of operation `kind`, or nil."
  (. by-kind kind))

(fn kind-names []
  "The operation kinds, sorted."
  (doto (icollect [_ d (ipairs operations)] d.kind) table.sort))

{:all operations : lookup : kind-names : variant : general}
