;; GLSL from a tape (src/sdf/lower.fnl): the functions the tape uses, the parameter
;; array, and the lines that map() and mapColor() run for each tree object. Output is
;; deterministic: the same tape gives the same text.

;; `pairs` under another name: a loop over `pairs` by that name is LuaJIT's ITERN,
;; which Debian 12's LuaJIT ends early once despecialised (see src/util/wire.fnl).
(local each-pair pairs)

(local primitives (require :src.sdf.primitives))
(local strategies (require :src.sdf.strategies))

(local swizzles ["x" "y" "z" "w"])

(fn float-literal [v]
  "`v` as a GLSL float: nine significant digits give back the same float32, always
with a decimal point or an exponent."
  (let [s (string.format "%.9g" v)]
    (if (or (s:find "[%.e]") (s:find "inf") (s:find "nan")) s (.. s ".0"))))

(fn literal [vals]
  (if (= 1 (length vals)) (float-literal (. vals 1))
      (.. "vec" (length vals) "(" (table.concat (icollect [_ v (ipairs vals)] (float-literal v)) ", ")
          ")")))


;; Material registers: vec4 (colour, mirror amount), or in the modern model mat2x4
;; (that, then roughness and emission): see :material-size in src/sdf/lower.fnl.
(local material-types {4 {:type "vec4" :zero "vec4(0.0)" :mix "mix"}
                       8 {:type "mat2x4" :zero "mat2x4(0.0)" :mix "mixMaterial"}})

;; An emission's context, `cx`, passed to every function below (none keeps state of
;; its own, so emission is reentrant):
;;   :rows-read  the tape's rows the code emitted reads (row -> true): only those are
;;               copied once per pixel (see load-once in src/render/codegen.fnl); one
;;               table shared by every context derived from the first
;;   :group      where the arguments being emitted live: nil for the tape's own rows
;;               (uTape), or an instance group's bank, whose rows are read at
;;               base + row + stride * i in the group's loop
;;   :along?     while a march's distance is emitted: grids bound their unlisted
;;               members along the ray rd, not only around the point (grid.glsl's
;;               gridCellAlong)
;;   :mt         the material registers' type (material-types)

(fn new-context []
  "A context for emitting one shader's code (see above): give it to each of the
*-terms functions of that shader, then `reads` says which tape rows they read."
  {:rows-read {} :along? false :mt (. material-types 4)})

(fn derived [cx key value]
  ;; `cx` with `key` set to `value` (nil too); the same rows-read.
  (doto (collect [k v (each-pair cx)] k v) (tset key value)))

(fn reads [cx]
  "The tape's rows the code emitted with context `cx` (or one derived from it) reads:
row -> true."
  cx.rows-read)

(fn row-expr [cx row]
  (let [group cx.group]
    (if group
        (let [at (+ group.base row)
              index (.. (or group.index "i") " * " group.stride (if (= at 0) "" (.. " + " at)))]
          ;; In a loop over a grid cell's list, a member's first row sits at its slot;
          ;; a bank in a texture (src/sdf/grid.fnl) is read through bankRow.
          (if (and group.slot (= row 0)) (.. "gridFirst(" group.slot ")")
              group.texture? (.. "bankRow(" index ")")
              (.. "uInstances[" index "]")))
        (do (tset cx.rows-read row true)
            (.. "uTape[" row "]")))))

(fn arg-expr [cx ref]
  (if ref.literal (literal ref.literal)
      (let [s (fcollect [i 1 ref.size] (. swizzles (+ ref.offset i)))]
        (.. (row-expr cx ref.row) "." (table.concat s)))))

(fn args-list [cx args]
  ;; An argument followed by one marked :estimate? (see :estimates? in lower.fnl)
  ;; is that one's value where the field is read as an estimate (gEstimate).
  (let [out []]
    (each [i a (ipairs args)]
      (let [nxt (. args (+ i 1))]
        (if a.estimate? nil
            (?. nxt :estimate?)
            (table.insert out (.. "(gEstimate ? " (arg-expr cx nxt) " : " (arg-expr cx a) ")"))
            (table.insert out (arg-expr cx a)))))
    out))

(fn reg [cx name]
  ;; p0 is map()'s own point; a group whose bank is in a texture reads its rows
  ;; about the bank's anchor, so its members are evaluated at pg = p - uBankOrigin.
  (let [group cx.group]
    (if (= name "p0") (or (?. group :p0) (if (?. group :texture?) "pg" "p")) name)))

(fn call [cx fname first args ?last]
  (let [parts [first (unpack (args-list cx args))]]
    (when ?last (table.insert parts ?last))
    (.. fname "(" (table.concat parts ", ") ")")))

(fn weight-name [form]
  (.. "w" (form.glsl-name:sub 3)))

(var emit-code nil)

(fn emit-cells [cx out ins materials?]
  ;; The child in each cell, the nearest kept.
  (let [c (.. "c" (ins.dout:sub 2))
        mt cx.mt
        body []]
    (table.insert out (.. "float " ins.dout " = 10000000000.0;"))
    (when materials? (table.insert out (.. mt.type " " ins.mout " = " mt.zero ";")))
    (table.insert out (.. "for (int " c " = 0; " c " < " ins.count "; " c "++) {"))
    ;; The cell index is the last argument.
    (table.insert body (.. "vec3 " ins.cell-p " = "
                           (call cx ins.desc.glsl-name (reg cx ins.pin) ins.args c) ";"))
    (emit-code cx body ins.body materials?)
    (if materials?
        (table.insert body (.. "if (" ins.body-d " < " ins.dout ") { " ins.dout " = "
                               ins.body-d "; " ins.mout " = " ins.body-m "; }"))
        (table.insert body (.. ins.dout " = min(" ins.dout ", " ins.body-d ");")))
    (each [_ l (ipairs body)] (table.insert out (.. "    " l)))
    (table.insert out "}")))

(fn emit-near-cells [cx out ins materials?]
  ;; The child in the point's own cell (0), each neighbour's copy by its box (see
  ;; :near? in src/sdf/lower.fnl); a neighbour clamped onto the own cell (past the
  ;; end of a limited repetition) counts no box.
  (let [c (.. "c" (ins.dout:sub 2))
        {: p : code : bout} ins.near?
        body []
        near []]
    (table.insert out (.. "float " ins.dout ";"))
    (when materials? (table.insert out (.. cx.mt.type " " ins.mout ";")))
    (table.insert out "{")
    (table.insert body (.. "vec3 " ins.cell-p " = "
                           (call cx ins.desc.glsl-name (reg cx ins.pin) ins.args "0") ";"))
    (emit-code cx body ins.body materials?)
    (table.insert body (.. ins.dout " = " ins.body-d ";"))
    (when materials? (table.insert body (.. ins.mout " = " ins.body-m ";")))
    (table.insert body (.. "for (int " c " = 1; " c " < " ins.count "; " c "++) {"))
    (table.insert near (.. "vec3 " p " = " (call cx ins.desc.glsl-name (reg cx ins.pin) ins.args c) ";"))
    (emit-code cx near code false)
    (table.insert near (.. ins.dout " = min(" ins.dout ", " p " == " ins.cell-p
                           " ? 10000000000.0 : " bout ");"))
    (each [_ l (ipairs near)] (table.insert body (.. "    " l)))
    (table.insert body "}")
    (each [_ l (ipairs body)] (table.insert out (.. "    " l)))
    (table.insert out "}")))

(fn emit-blend [cx out ins materials?]
  ;; A loop over the members' rows in the instance bank (see :blend in lower.fnl),
  ;; or over those the point's grid cell lists, the others bounded.
  (let [n (ins.dout:sub 2)
        j (.. "j" n)
        mt cx.mt
        args (args-list cx ins.args)
        fold (fn [da db] (table.concat [da db (unpack args)] ", "))
        {: code :d bd :m bm} ins.members
        member-cx (derived cx :group {:base ins.base :stride ins.stride :index j
                                      :texture? ins.texture? :p0 (reg cx "p0")
                                      :slot (when ins.grid (.. "s" n " + k" n))})
        body (emit-code member-cx [] code materials?)
        add (fn [indent line] (table.insert out (.. (string.rep "    " indent) line)))
        inner (if ins.grid 2 1)]
    (add 0 (.. "float " ins.dout " = uDrawDist;"))
    (when materials? (add 0 (.. mt.type " " ins.mout " = " mt.zero ";")))
    (if ins.grid
        ;; The children the point's cell lists, the others' bound (grid.glsl).
        (do (add 0 "{")
            (add 1 (.. "int s" n ";"))
            (add 1 (.. "int c" n ";"))
            (add 1 (.. "float b" n " = "
                       (if (and cx.along? ins.along?)
                           (.. "gridCellAlong(" ins.grid ", " (reg cx ins.pin) ", rd, s" n ", c" n ");")
                           (.. "gridCell(" ins.grid ", " (reg cx ins.pin) ", s" n ", c" n ");"))))
            (add 1 (.. "for (int k" n " = 0; k" n " < c" n "; k" n "++) {"))
            (add 2 (.. "int " j " = gridMember(s" n " + k" n ");")))
        (add 0 (.. "for (int " j " = 0; " j " < " ins.count "; " j "++) {")))
    (each [_ l (ipairs body)] (add inner l))
    (when materials?
      (add inner (.. ins.mout " = " mt.mix "(" bm ", " ins.mout ", "
                     (weight-name ins.desc) "(" (fold ins.dout bd) "));")))
    (add inner (.. ins.dout " = " ins.desc.glsl-name "(" (fold ins.dout bd) ");"))
    (add (- inner 1) "}")
    (when ins.grid
      (add 1 (.. ins.dout " = min(" ins.dout ", b" n ");"))
      (add 0 "}"))))

(fn emit-material [cx out ins]
  ;; A material's rows read into its register.
  (let [lit ins.literal
        row (fn [k] (if lit (literal (fcollect [i 1 4] (. lit (+ (* 4 k) i))))
                        (row-expr cx (+ ins.row k))))]
    (table.insert out (if (= cx.mt.type "vec4")
                          (.. "vec4 " ins.mout " = " (row 0) ";")
                          (.. "mat2x4 " ins.mout " = mat2x4(" (row 0) ", " (row 1)
                              ");")))))

(fn emit-mix [cx out ins]
  ;; A combination's material: its operands' blended by its weight.
  (table.insert out (.. cx.mt.type " " ins.mout " = " cx.mt.mix "(" ins.mb ", " ins.ma ", "
                        (call cx (weight-name ins.desc) (.. ins.da ", " ins.db) ins.args)
                        ");")))

(fn emit-instr [cx out ins materials?]
  ;; With `materials?` :only, the material lines alone (an object's materials
  ;; computed after its distance: see deferred-materials?).
  (if (= materials? :only)
      (case ins.op
        :material (emit-material cx out ins)
        :combine (emit-mix cx out ins))
      (case ins.op
        :prim (table.insert out (.. "float " ins.dout " = "
                                    (call cx ins.desc.glsl-name (reg cx ins.pin) ins.args) ";"))
        :material (when materials? (emit-material cx out ins))
        :point (table.insert out (.. "vec3 " ins.pout " = "
                                     (call cx ins.desc.glsl-name (reg cx ins.pin) ins.args) ";"))
        :post (table.insert out (.. "float " ins.dout " = "
                                    (call cx ins.desc.glsl-name (.. ins.din ", " (reg cx ins.pin)) ins.args) ";"))
        :distance (table.insert out (.. "float " ins.dout " = "
                                        (call cx ins.desc.glsl-name
                                              (.. ins.din ", " (reg cx ins.pin)) ins.args) ";"))
        :far (table.insert out (.. "float " ins.dout " = max(" ins.din ", " ins.bin ");"))
        :divide (table.insert out (string.format "float %s = %s * %.9g;  // Lipschitz %.6g"
                                                 ins.dout ins.din (/ 1 ins.k) ins.k))
        :combine (do
                   (table.insert out (.. "float " ins.dout " = "
                                         (call cx ins.desc.glsl-name (.. ins.da ", " ins.db) ins.args) ";"))
                   (when materials? (emit-mix cx out ins)))
        :cells (if ins.near? (emit-near-cells cx out ins materials?) (emit-cells cx out ins materials?))
        :blend (emit-blend cx out ins materials?)
        _ (error (.. "emit-glsl: unknown instruction " (tostring ins.op))))))

(set emit-code
     (fn [cx out code materials?]
       (each [_ ins (ipairs code)] (emit-instr cx out ins materials?))
       out))

(fn text-lines [text]
  "The lines of `text`."
  (icollect [line (: (.. text "\n") :gmatch "([^\n]*)\n")] line))


(fn functions [tape ?defined]
  "GLSL definitions of every function the tape uses, in first-use order,
but those named in `?defined` (GLSL name -> true: already in the shader; those
written here are added to it)."
  (let [out []
        defined (or ?defined {})]
    (each [_ u (ipairs tape.used)]
      (when (not (. defined u.name))
        (tset defined u.name true)
        (table.insert out u.desc.glsl)))
    (when (= tape.material-size 8)
      (table.insert out (.. "// Blends two-row materials as mix() blends vec4 ones.\n"
                            "mat2x4 mixMaterial(mat2x4 a, mat2x4 b, float w) {\n"
                            "    return a * (1.0 - w) + b * w;\n}")))
    (let [lines []]
      (each [i text (ipairs out)]
        (when (> i 1) (table.insert lines ""))
        (each [_ line (ipairs (text-lines text))] (table.insert lines line)))
      lines)))

(fn gradient-name [desc]
  "The GLSL name of primitive `desc`'s exact gradient (sdX -> gradX)."
  (pick-values 1 (desc.glsl-name:gsub "^sd" "grad")))

(fn gradient-functions [tape which ?defined]
  "The exact gradients (:gradient-glsl) of the descriptors that leaf objects (see
lower.fnl's :leaf) for which `which` is true draw with, each once, and what they call
(:gradient-needs names another descriptor's), but those in `?defined` (added to
it)."
  (let [defined (or ?defined {})
        out []]
    (fn add [desc]
      (let [name (gradient-name desc)]
        (when (not (. defined name))
          (when desc.gradient-needs
            (add (assert (accumulate [found nil _ d (ipairs primitives.all) &until found]
                           (when (= (gradient-name d) desc.gradient-needs) d)))))
          (tset defined name true)
          (when (> (length out) 0) (table.insert out ""))
          (each [_ l (ipairs (text-lines desc.gradient-glsl))] (table.insert out l)))))
    (each [_ o (ipairs tape.objects)]
      (let [prim (?. o :leaf :prim)]
        (when (and prim prim.desc.gradient-glsl (which o)) (add prim.desc))))
    out))

(fn declare [ty name ?count ?comment ?loop?]
  "A uniform's declaration as data (codegen writes it, and its copy; see load-once
there): GLSL type, name, array size, comment, and whether code indexes it by a
variable (then it is read where used, never copied)."
  (let [trailer (if ?comment (.. "  // " ?comment) "")]
    {:declare {:type ty : name :count ?count :loop? ?loop? : trailer
               :text (.. "uniform " ty " " name (if ?count (.. "[" ?count "]") "") ";" trailer)}}))

;; The tape's rows as a texture (a plan's :tape-texture?, on llvmpipe): row r is the
;; texel (r mod width, floor(r / width)) of an rgba32f image this wide (llvmpipe takes
;; 16384).
(local tape-texture-width 1024)

;; The longest uniform array that load-once (src/render/codegen.fnl) copies element by
;; element although code indexes it in a loop (the lights, the bounding spheres): a
;; loop this short over a constant count is unrolled, so each element is read at a
;; constant index; a longer array stays a uniform, read where used.
(local max-copied-array 8)

(fn tape-texel [row]
  "The texel that holds the tape's row `row` (0-based) when the rows travel as a
texture: x, y."
  (values (% row tape-texture-width) (math.floor (/ row tape-texture-width))))

(fn declarations [tape]
  "The parameter arrays' declarations (see `declare`): the tape's rows, read at
constant indices (marked :rows?: codegen may read them from a texture), and the
instance groups', in loops."
  [(if (> (length tape.rows) 0)
       [(doto (declare "vec4" "uTape" (length tape.rows) "tree parameters and materials")
          (tset :declare :rows? true))]
       [])
   (if (and (> (length tape.instances.rows) 0) (not tape.instances.texture?))
       [(declare "vec4" "uInstances" (length tape.instances.rows)
                 "instance groups' parameters and materials, one stride each" true)]
       [])])

;;; Helpers for the strategies' terms (src/sdf/strategies/): an object's code, its
;;; comment, its block in a minimum, its material's tail, its gradient.

(fn object-comment [o ?more]
  "A comment naming object `o`: its path and what it draws (under the translation its
:pos makes), then `?more`."
  (.. "// " o.info.path ": "
      (if (and o.info.implicit? (. o.info.children 1)) (. o.info.children 1 :kind) o.info.kind)
      (or ?more "")))

(fn indented [lines]
  "`lines` (nested lists flattened) indented by four spaces."
  (let [out []]
    (fn add [ls]
      (each [_ l (ipairs ls)]
        (if (= (type l) :table) (add l) (table.insert out (if (= l "") "" (.. "    " l))))))
    (add lines)
    out))

(fn guarded-lines [cx o materials? tail]
  "Lines of object `o`'s code, then the lines `tail` (which use its distance). With a
guard (see src/sdf/lower.fnl), the code after the guard's box and `tail` run only
where that box is nearer than d: elsewhere the object's value, at least the box's,
could not lower d."
  (if o.guard
      (let [head (emit-code cx [] (fcollect [i 1 o.guard.head] (. o.code i)) materials?)
            rest (emit-code cx [] (fcollect [i (+ o.guard.head 1) (length o.code)] (. o.code i))
                            materials?)]
        (table.insert head (.. "if (" o.guard.bout " < d) {"))
        (each [_ l (ipairs (indented rest))] (table.insert head l))
        (each [_ l (ipairs (indented tail))] (table.insert head l))
        (table.insert head "}")
        head)
      (let [lines (emit-code cx [] o.code materials?)]
        (each [_ l (ipairs tail)] (table.insert lines l))
        lines)))

(fn object-body [cx o id materials? open tail]
  "Object `o`'s block in a minimum: opened by `(open id)`, its code and then `(tail
id)` (lines using its distance); `id` is its number as GLSL."
  [(open id) (indented (guarded-lines cx o materials? (tail id))) "}"])

(fn open-block [] "{")

(fn minimum-tail [o]
  "A tail for object-body: the object's distance folded into d."
  #[(.. "d = min(d, " o.dout ");")])

(fn taken-open [id]
  "An opening for object-body in mapObject: taken when every object is (`all`) or
`only` is this one, and `skip` is not."
  (.. "if ((all || only == " id ") && skip != " id ") {"))

(fn color-taken [o id mirrors? modern?]
  ;; The nearest so far keeps its distance and colour (with `mirrors?` or two-row
  ;; materials, its mirror amount; with those, its second row), and with `id` its
  ;; number in gObject.
  (let [row (when o.mout (if modern? (.. o.mout "[0]") o.mout))]
    (.. "d = " o.dout "; color = " row ".rgb;"
        (if (or mirrors? modern?) (.. " gMirror = " row ".a;") "")
        (if modern? (.. " gMaterial = " o.mout "[1];") "")
        (if id (.. " gObject = " id ";") ""))))

(fn color-tail [o ?first mirrors? modern?]
  "A tail for object-body in mapColor: the nearest keeps its colour (with `mirrors?`
or two-row materials, its mirror amount; with those, its second row), and with
`?first` its number in gObject."
  #[(.. "if (" o.dout " < d) { " (color-taken o (when ?first $) mirrors? modern?) " }")])

(fn deferred-materials? [o]
  "Whether object `o`'s materials may be computed after its distance, at the end of
its code, only where it is the nearest so far: no repetition or blend in it (those
keep the nearest cell's or member's material inside their loop)."
  (accumulate [ok? true _ ins (ipairs o.code)]
    (and ok? (not= ins.op :cells) (not= ins.op :blend))))

(fn either-tail [cx o mirrors? modern?]
  "A tail for object-body in mapObject(p, only, skip, materials, color): with
`materials` (mapColor's query, every object) the nearest keeps its colour and its
number in gObject, its materials computed then (deferred-materials?: else its code
computes them as it goes); without, its distance folded into d. Its code is then
written once for both."
  (let [cx (derived cx :mt (or cx.mt (. material-types (if modern? 8 4))))
        later (if (deferred-materials? o) (emit-code cx [] o.code :only) [])]
    #["if (materials) {"
      (indented [(.. "if (" o.dout " < d) {")
                 (indented [later (color-taken o $ mirrors? modern?)])
                 "}"])
      "} else {"
      (indented [(.. "d = min(d, " o.dout ");")])
      "}"]))

(fn either-terms [color-lines object-lines]
  "A strategy's term in mapObject(p, only, skip, materials, color) from its mapColor
lines and its distance-only lines, when it has no form that serves both."
  ["if (materials) {" (indented color-lines) "} else {" (indented object-lines) "}"])

(fn leaf-gradient [cx o action]
  "A leaf object's exact normal: its translations, then its primitive's gradient
(see lower.fnl's :leaf); `action` is \"n = \" or \"return \"."
  (let [{: points : prim} o.leaf]
    [(emit-code cx [] points false)
     (.. action (call cx (gradient-name prim.desc) (reg cx prim.pin) prim.args) ";")]))

(fn leaf-exact? [o]
  "Whether leaf object `o`'s primitive has its gradient in closed form."
  (not= nil (?. o :leaf :prim :desc :gradient-glsl)))

(fn plane-block [o]
  "A function of a context giving half-space `o`'s block for planesHit(ro, rd): t
lowered to where the ray enters it, 0 from inside, t = -s / v for s its distance at
the origin and v the ray's rate along its normal (the gradient). `p` is the ray's
origin."
  (let [{: points : prim} o.leaf]
    #["{"
      (indented [(emit-code $ [] points false)
                 (.. "float s = " (call $ prim.desc.glsl-name (reg $ prim.pin) prim.args) ";")
                 (.. "float v = dot(rd, " (call $ (gradient-name prim.desc) (reg $ prim.pin)
                                                  prim.args) ");")
                 "if (s <= 0.0) {"
                 "    t = 0.0;"
                 "} else if (v < 0.0) {"
                 "    t = min(t, -s / v);"
                 "}"])
      "}"]))

(fn written-terms [block selected]
  "The :glsl terms of a strategy that writes its objects' code out (a tree, an
instance group), from its `block` (fn [cx o first materials? open tail]: an object's
block in a minimum, see object-body) and `selected` (fn [cx o first lines-fn]: lines
run when gObject is its object's number): :distance, :color, :gradient and :exact?;
the strategy adds :object and :planes."
  {:distance (fn [cx o] (block cx o 0 false open-block (minimum-tail o)))
   :color (fn [cx o ?first mirrors? modern?]
            (block cx o (or ?first 0) true open-block (color-tail o ?first mirrors? modern?)))
   :gradient (fn [cx o first action]
               (when (leaf-exact? o)
                 (selected cx o first #(leaf-gradient $ o action))))
   :exact? leaf-exact?})

;;; The shader's queries: each tape object's terms through its strategy.

(fn objects-of [tape ?which]
  (icollect [_ o (ipairs tape.objects)] (when (or (not ?which) (?which o)) o)))

(fn glsl-of [o]
  (. (strategies.of o) :glsl))

(fn distance-terms [cx tape ?finite? ?along?]
  "Lines for map(), emitted with context `cx` (see new-context): each tape object's
distance, folded into d. With `?finite?`, mapFinite's: each object a bounded march
steps by (its strategy's :marched?), and cx.finite? set for one that stands for
several (the interpreter's: not its half-spaces). With `?along?`, a march's: rd is
its ray's direction, and a grid's bound reaches along it (see gridCellAlong)."
  (let [cx (doto (derived cx :along? (= true ?along?)) (tset :finite? (= true ?finite?)))
        ?which (when ?finite? #((. (strategies.of $) :marched?) $))]
    (icollect [_ o (ipairs (objects-of tape ?which))]
      ((. (glsl-of o) :distance) cx o))))

(fn some-terms [cx tape flag]
  "Lines for mapSome(p, flag): map()'s, the half-spaces' (the objects a bounded march
does not step by) only where the GLSL boolean `flag` holds, so a call with a constant
folds to map or mapFinite; cx.finite? is the expression `!flag` for an object that
stands for several (the interpreter's)."
  (let [cx (doto (derived cx :along? false) (tset :finite? (.. "!" flag)))]
    (icollect [_ o (ipairs tape.objects)]
      (let [lines ((. (glsl-of o) :distance) cx o)]
        (if ((. (strategies.of o) :marched?) o)
            lines
            [(.. "if (" flag ") {") (indented lines) "}"])))))

(fn color-terms [cx tape mirrors? ?first]
  "Lines for mapColor(): as map(), keeping the nearest object's colour in `color` (and
its mirror amount in gMirror when `mirrors?`; with two-row materials, always, and
the second row in gMaterial). With `?first`, also its number in gObject: the
objects are numbered from it in tape order, an instance group's members one each."
  (let [cx (derived cx :mt (. material-types tape.material-size))
        modern? (= tape.material-size 8)]
    (icollect [_ o (ipairs tape.objects)]
      ((. (glsl-of o) :color) cx o ?first mirrors? modern?))))

(fn object-terms [cx tape first mirrors?]
  "Lines for mapObject(p, only, skip, materials, color): the distance of the object
`only` numbers (numbered from `first` as color-terms does) alone, set in d; with
`only` -1 (`all`) every object's but the one `skip` numbers (-1: none), folded into d
as map() folds them; with `materials`, mapColor's query (as color-terms, with
`mirrors?`, numbering the objects in gObject). Each object is written once for every
case where its strategy can (GLSL compilers inline every call: each copy of the scene
is its share of the compile, and normal-crease.glsl's surfaceAt calls it in one
loop)."
  (let [cx (derived cx :mt (. material-types tape.material-size))
        modern? (= tape.material-size 8)]
    (icollect [_ o (ipairs tape.objects)]
      ((. (glsl-of o) :object) cx o first mirrors? modern?))))

(fn exact? [o]
  "Whether object `o` has its exact normal in closed form (its strategy's :exact?)."
  ((. (glsl-of o) :exact?) o))

(fn gradient-terms [cx tape first action]
  "Lines for calcNormal: each object with an exact normal (exact?) gives it when
gObject is its number (counted from `first`); `action` is \"n = \" or \"return \"."
  (icollect [_ o (ipairs tape.objects)]
    ((. (glsl-of o) :gradient) cx o first action)))

(fn plane-terms [cx tape]
  "Lines for planesHit(ro, rd): each half-space object's (lower.fnl's :half-space?: a
leaf whose primitive is solid below a plane, met in closed form; see plane-block)."
  (icollect [_ o (ipairs tape.objects)]
    ((. (glsl-of o) :planes) cx o)))

{: functions : gradient-functions : declarations : declare : new-context : reads
 : distance-terms : some-terms : color-terms : object-terms : gradient-terms : plane-terms
 : exact? : text-lines : float-literal : tape-texture-width : tape-texel : gradient-name
 : max-copied-array
 ;; For the strategies' terms (src/sdf/strategies/):
 : derived : emit-code : object-comment : indented : guarded-lines : object-body : open-block
 : minimum-tail : taken-open : color-tail : either-tail : either-terms : deferred-materials? : leaf-gradient : leaf-exact? : plane-block
 : written-terms}
