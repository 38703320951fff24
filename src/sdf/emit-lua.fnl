;; The CPU evaluator from a tape (src/sdf/lower.fnl): Lua source, one function per tree
;; object, compiled with load and run in double precision. It reads the same tape as
;; the GLSL emitter and calls each descriptor's :cpu form where the GLSL calls its
;; function, so the two evaluators cannot drift apart.

(local grid (require :src.sdf.grid))
(local strategies (require :src.sdf.strategies))

(local max-locals 150)   ; Lua allows 200 locals per function; beyond, a table holds them

;; Material components: colour and mirror amount, and in the modern model roughness,
;; emission and two spare (see :material-size in src/sdf/lower.fnl).
(local material-components {4 ["r" "g" "b" "a"] 8 ["r" "g" "b" "a" "k" "e" "u" "v"]})

(fn new-emitter [table-mode? material-size group?]
  (let [e {:lines [] :fns [] :fn-index {} : table-mode? : group?
           :comps (. material-components (or material-size 4))}]
    (fn e.fn-ref [f]
      (when (not (. e.fn-index f))
        (table.insert e.fns f)
        (tset e.fn-index f (length e.fns)))
      (.. "F[" (. e.fn-index f) "]"))
    (fn e.r [name] (if e.table-mode? (.. "R." name) name))
    (fn e.decl [name] (if e.table-mode? (.. "R." name) (.. "local " name)))
    (fn e.line [indent s] (table.insert e.lines (.. (string.rep "  " indent) s)))
    e))

(fn slot [e n]
  ;; S is 1-based and flat: row r, offset o, component k is S[r * 4 + o + k]; in an
  ;; instance group's function, S[B + ...] with B its member's first (see compile);
  ;; in a blend's loop, the instance bank at its child's first (e.bank).
  (if e.bank (.. e.bank.name "[" e.bank.base " + " n "]")
      e.group? (.. "S[B + " n "]")
      (.. "S[" n "]")))

(fn arg-values [e args]
  ;; An argument followed by one marked :estimate? (see :estimates? in lower.fnl)
  ;; is that one's value in an estimate's function (e.estimate?).
  (let [out []]
    (each [i a (ipairs args)]
      (let [nxt (. args (+ i 1))
            a (if (and e.estimate? (?. nxt :estimate?)) nxt a)]
        (when (not (. args i :estimate?))
          (for [k 1 a.size]
            (table.insert out (slot e (+ (* a.row 4) a.offset k)))))))
    out))

(fn point [e name]
  (if (= name "p0") "x, y, z"
      (.. (e.r (.. name "x")) ", " (e.r (.. name "y")) ", " (e.r (.. name "z")))))

(fn point-decl [e name]
  (if e.table-mode?
      (.. (e.r (.. name "x")) ", " (e.r (.. name "y")) ", " (e.r (.. name "z")))
      (.. "local " name "x, " name "y, " name "z")))

(fn material [e name]
  (table.concat (icollect [_ c (ipairs e.comps)] (e.r (.. name c))) ", "))

(fn material-decl [e name]
  (if e.table-mode?
      (material e name)
      (.. "local " (table.concat (icollect [_ c (ipairs e.comps)] (.. name c)) ", "))))

(fn call [e f first args ?rest]
  (let [parts [first]]
    (each [_ v (ipairs (arg-values e args))] (table.insert parts v))
    (when ?rest (table.insert parts ?rest))
    (.. (e.fn-ref f) "(" (table.concat parts ", ") ")")))

(var emit-code nil)

(fn emit-instr [e ins materials? indent]
  (case ins.op
    :prim (e.line indent (.. (e.decl ins.dout) " = " (call e ins.desc.cpu (point e ins.pin) ins.args)))
    :material (when materials?
                (let [base (* ins.row 4)]
                  (e.line indent (.. (material-decl e ins.mout) " = "
                                     (table.concat (fcollect [k 1 (length e.comps)]
                                                     (slot e (+ base k)))
                                                   ", ")))))
    :point (e.line indent (.. (point-decl e ins.pout) " = "
                              (call e ins.desc.cpu (point e ins.pin) ins.args)))
    :post (e.line indent (.. (e.decl ins.dout) " = "
                             (call e ins.desc.cpu (.. (e.r ins.din) ", " (point e ins.pin)) ins.args)))
    :distance (e.line indent (.. (e.decl ins.dout) " = "
                                 (call e ins.desc.cpu (.. (e.r ins.din) ", " (point e ins.pin))
                                       ins.args)))
    :far (e.line indent (.. (e.decl ins.dout) " = math.max(" (e.r ins.din) ", " (e.r ins.bin) ")"))
    :divide (e.line indent (string.format "%s = %s / %.17g" (e.decl ins.dout) (e.r ins.din) ins.k))
    :combine
    (let [da (e.r ins.da) db (e.r ins.db)]
      (e.line indent (.. (e.decl ins.dout) " = " (call e ins.desc.cpu (.. da ", " db) ins.args)))
      (when materials?
        (let [w (.. "w" (ins.dout:sub 2))]
          (e.line indent (.. (e.decl w) " = " (call e ins.desc.cpu-weight (.. da ", " db) ins.args)))
          ;; GLSL's mix(mb, ma, w) = mb * (1 - w) + ma * w.
          (e.line indent (.. (material-decl e ins.mout) " = "
                             (table.concat
                              (icollect [_ c (ipairs e.comps)]
                                (let [a (e.r (.. ins.ma c)) b (e.r (.. ins.mb c))]
                                  (.. b " * (1 - " (e.r w) ") + " a " * " (e.r w))))
                              ", "))))))
    :cells
    (if ins.near?
        ;; The own cell's child, each neighbour by its copy's box (see emit-glsl).
        (let [c (.. "c" (ins.dout:sub 2))
              dout (e.r ins.dout)
              {: p : code : bout} ins.near?
              same (.. (e.r (.. p "x")) " == " (e.r (.. ins.cell-p "x")) " and "
                       (e.r (.. p "y")) " == " (e.r (.. ins.cell-p "y")) " and "
                       (e.r (.. p "z")) " == " (e.r (.. ins.cell-p "z")))]
          (e.line indent (.. (point-decl e ins.cell-p) " = "
                             (call e ins.desc.cpu (.. "0, " (point e ins.pin)) ins.args)))
          (emit-code e ins.body materials? indent)
          (e.line indent (.. (e.decl ins.dout) " = " (e.r ins.body-d)))
          (when materials?
            (e.line indent (.. (material-decl e ins.mout) " = " (material e ins.body-m))))
          (e.line indent (.. "for " c " = 1, " (- ins.count 1) " do"))
          (e.line (+ indent 1) (.. (point-decl e p) " = "
                                   (call e ins.desc.cpu (.. c ", " (point e ins.pin)) ins.args)))
          (emit-code e code false (+ indent 1))
          (e.line (+ indent 1) (.. "if not (" same ") and " (e.r bout) " < " dout " then "
                                   dout " = " (e.r bout) " end"))
          (e.line indent "end"))
    (let [c (.. "c" (ins.dout:sub 2))
          dout (e.r ins.dout)]
      (e.line indent (.. (e.decl ins.dout) " = 1e30"))
      (when materials? (e.line indent (.. (material-decl e ins.mout) " = "
                                          (table.concat (icollect [_ _ (ipairs e.comps)] "0") ", "))))
      (e.line indent (.. "for " c " = 0, " (- ins.count 1) " do"))
      (e.line (+ indent 1) (.. (point-decl e ins.cell-p) " = "
                               (call e ins.desc.cpu (.. c ", " (point e ins.pin)) ins.args)))
      (emit-code e ins.body materials? (+ indent 1))
      (let [bd (e.r ins.body-d)]
        (e.line (+ indent 1)
                (.. "if " bd " < " dout " then " dout " = " bd
                    (if materials? (.. "; " (material e ins.mout) " = " (material e ins.body-m)) "")
                    " end")))
      (e.line indent "end")))
    :blend
    (let [n (ins.dout:sub 2)
          dout (e.r ins.dout)
          j (.. "j" n)
          base (.. "BJ" n)
          {: code :d bd :m bm} ins.members
          op-args (fn [] (.. dout ", " (e.r bd)
                             (table.concat (icollect [_ v (ipairs (arg-values e ins.args))] (.. ", " v)))))
          g ins.grid-data
          outer e.bank
          inner (+ indent 1)]
      (e.line indent (.. (e.decl ins.dout) " = 1e30"))
      (when materials? (e.line indent (.. (material-decl e ins.mout) " = "
                                          (table.concat (icollect [_ _ (ipairs e.comps)] "0") ", "))))
      (if g
          ;; The children the point's cell lists, the others' bound (src/sdf/grid.fnl).
          ;; Along a march's ray dx dy dz when its point is the evaluator's
          ;; translated (gridCellAlong's), else around the point.
          (let [query (e.fn-ref (if ins.along?
                                    (fn [x y z dx dy dz] (grid.query g x y z dx dy dz 1e30))
                                    (fn [x y z] (grid.query g x y z))))]
            (e.line indent (.. "local s" n ", c" n ", b" n " = " query "(" (point e ins.pin)
                               (if ins.along? ", dx, dy, dz" "") ")"))
            (e.line indent (.. "for k" n " = s" n " + 1, s" n " + c" n " do"))
            (e.line inner (.. "local " j " = " (e.fn-ref g.records) "[k" n "]")))
          (e.line indent (.. "for " j " = 0, " (- ins.count 1) " do")))
      (e.line inner (.. "local " base " = (" ins.base " + " j " * " ins.stride ") * 4"))
      (set e.bank {:name (e.fn-ref e.instances) : base})
      (emit-code e code materials? inner)
      (set e.bank outer)
      (when materials?
        (let [w (.. "w" n)]
          (e.line inner (.. "local " w " = " (e.fn-ref ins.desc.cpu-weight) "(" (op-args) ")"))
          ;; GLSL's mix(mb, m, w) = mb * (1 - w) + m * w.
          (e.line inner (.. (material e ins.mout) " = "
                            (table.concat
                             (icollect [_ c (ipairs e.comps)]
                               (let [a (e.r (.. ins.mout c)) b (e.r (.. bm c))]
                                 (.. b " * (1 - " w ") + " a " * " w)))
                             ", ")))))
      (e.line inner (.. dout " = " (e.fn-ref ins.desc.cpu) "(" (op-args) ")"))
      (e.line indent "end")
      (when g (e.line indent (.. "if b" n " < " dout " then " dout " = b" n " end"))))
    _ (error (.. "emit-lua: unknown instruction " (tostring ins.op)))))

(set emit-code
     (fn [e code materials? indent]
       (each [_ ins (ipairs code)] (emit-instr e ins materials? indent))))

(fn local-count [lines]
  ;; The locals `lines` declare (`local a, b = ...` counts two), inner blocks' too.
  (accumulate [n 0 _ l (ipairs lines)]
    (case (l:match "^%s*local ([^=]*) =")
      names (+ n 1 (select 2 (names:gsub "," "")))
      _ n)))

(fn function-lines [e o what]
  ;; The function of object `o` that returns its distance (:distance), that and its
  ;; material (:material), or its exact normal (:gradient, a leaf's; see lower.fnl).
  ;; (dx dy dz: a march's ray direction, or nil; see :blend.)
  (when e.table-mode? (e.line 0 "local R = {}"))
  (e.line 0 "FN[#FN + 1] = function(x, y, z, dx, dy, dz)")
  (if (= what :gradient)
      (let [{: points : prim} o.leaf]
        (emit-code e points false 1)
        (e.line 1 (.. "return " (call e prim.desc.gradient (point e prim.pin) prim.args))))
      (let [materials? (= what :material)]
        (emit-code e o.code materials? 1)
        (e.line 1 (.. "return " (e.r o.dout) (if materials? (.. ", " (material e o.mout)) "")))))
  (e.line 0 "end"))

(fn flat-rows [rows]
  (let [out []]
    (each [_ row (ipairs rows)]
      (each [_ v (ipairs row)] (table.insert out v)))
    out))

(fn banks [tape]
  "The flat rows the evaluators of `tape` read: {:tape :instances}."
  {:tape (flat-rows tape.rows) :instances (flat-rows tape.instances.rows)})

(fn object-evaluators [tape o what banks into ?group]
  "Add object `o`'s CPU evaluator of `what` (see compile) to the list `into`: its code
compiled from Lua source, or false for a gradient its leaf has not; with `?group` (an
instance group: {:count :base :stride}), one per member, reading its rows from the
group's bank. Returns the source, if any."
  (if (and (= what :gradient) (not (?. o :leaf :prim :desc :gradient)))
      (for [_ 1 (if ?group ?group.count 1)] (table.insert into false))
      (let [emit (fn [table-mode?]
                   (let [e (doto (new-emitter table-mode? tape.material-size (not= nil ?group))
                             (tset :instances banks.instances)
                             (tset :estimate? (= what :estimate)))]
                     (e.line 0 "local S, F, FN, first, stride, count = ...")
                     (when ?group
                       (e.line 0 "for member = 0, count - 1 do")
                       (e.line 0 "local B = (first + member * stride) * 4"))
                     (function-lines e o what)
                     (when ?group (e.line 0 "end"))
                     e))
            ;; Locals while they fit; a table holds them in a function with more.
            e (let [e (emit false)]
                (if (or (= what :material) (> (local-count e.lines) max-locals)) (emit true) e))
            source (table.concat e.lines "\n")
            chunk (assert ((or _G.loadstring load) source (.. "=tape:" o.info.path)))]
        (if ?group
            (chunk banks.instances e.fns into ?group.base ?group.stride ?group.count)
            (chunk banks.tape e.fns into))
        source)))

(fn compile [tape]
  "CPU evaluators for `tape`'s objects, in world coordinates and double precision, one
per object number (an instance group's members one each, in order): {:distance
[(fn [x y z]) -> d] :material [(fn [x y z]) -> d r g b mirror (and with
:material-size 8: roughness emission and two spare)] :gradient [(fn [x y z]) -> nx ny
nz, or false where the object has no exact normal] :estimate [(fn [x y z]) -> d read
as an estimate of the distance: see :estimates? in lower.fnl; the :distance list
itself without them] :source text}. Each object's come from its drawing strategy
(src/sdf/strategies/)."
  (let [sources []
        banks (banks tape)
        out {:distance [] :material [] :gradient [] :estimate []}]
    (each [_ what (ipairs (if tape.estimates? [:distance :material :gradient :estimate]
                              [:distance :material :gradient]))]
      (each [_ o (ipairs tape.objects)]
        (let [source ((. (strategies.of o) :lua) tape o what banks (. out what))]
          (when source (table.insert sources source)))))
    (set out.source (table.concat sources "\n"))
    ;; Without estimates (tape.estimates?), the field read as an estimate is the
    ;; distance itself.
    (when (not tape.estimates?) (set out.estimate out.distance))
    out))

{: compile : object-evaluators : banks}
