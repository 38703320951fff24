;; GLSL from a tape (src/sdf/lower.fnl): the functions the tape uses, the parameter
;; array, and the lines that map() and mapColor() run for each tree object. Output is
;; deterministic: the same tape gives the same text.

(local primitives (require :src.sdf.primitives))

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

(fn arg-expr [ref]
  (if ref.literal (literal ref.literal)
      (let [s (fcollect [i 1 ref.size] (. swizzles (+ ref.offset i)))]
        (.. "uTape[" ref.row "]." (table.concat s)))))

(fn args-list [args]
  (icollect [_ a (ipairs args)] (arg-expr a)))

(fn reg [name]
  ;; p0 is map()'s own point.
  (if (= name "p0") "p" name))

(fn call [fname first args ?last]
  (let [parts [first (unpack (args-list args))]]
    (when ?last (table.insert parts ?last))
    (.. fname "(" (table.concat parts ", ") ")")))

(fn weight-name [form]
  (.. "w" (form.glsl-name:sub 3)))

(var emit-code nil)

;; Material registers: vec4 (colour, mirror amount), or in the modern model mat2x4
;; (that, then roughness and emission): see :material-size in src/sdf/lower.fnl.
(local material-types {4 {:type "vec4" :zero "vec4(0.0)" :mix "mix"}
                       8 {:type "mat2x4" :zero "mat2x4(0.0)" :mix "mixMaterial"}})

(var mt (. material-types 4))

(fn emit-instr [out ins materials?]
  (case ins.op
    :prim (table.insert out (.. "float " ins.dout " = "
                                (call ins.desc.glsl-name (reg ins.pin) ins.args) ";"))
    :material (when materials?
                (let [lit ins.literal
                      row (fn [k] (if lit (literal (fcollect [i 1 4] (. lit (+ (* 4 k) i))))
                                      (.. "uTape[" (+ ins.row k) "]")))]
                  (table.insert out (if (= mt.type "vec4")
                                        (.. "vec4 " ins.mout " = " (row 0) ";")
                                        (.. "mat2x4 " ins.mout " = mat2x4(" (row 0) ", " (row 1)
                                            ");")))))
    :point (table.insert out (.. "vec3 " ins.pout " = "
                                 (call ins.desc.glsl-name (reg ins.pin) ins.args) ";"))
    :post (table.insert out (.. "float " ins.dout " = "
                                (call ins.desc.glsl-name (.. ins.din ", " (reg ins.pin)) ins.args) ";"))
    :distance (table.insert out (.. "float " ins.dout " = "
                                    (call ins.desc.glsl-name
                                          (.. ins.din ", " (reg ins.pin)) ins.args) ";"))
    :far (table.insert out (.. "float " ins.dout " = max(" ins.din ", " ins.bin ");"))
    :divide (table.insert out (string.format "float %s = %s * %.9g;  // Lipschitz %.6g"
                                             ins.dout ins.din (/ 1 ins.k) ins.k))
    :combine (do
               (table.insert out (.. "float " ins.dout " = "
                                     (call ins.desc.glsl-name (.. ins.da ", " ins.db) ins.args) ";"))
               (when materials?
                 (table.insert out (.. mt.type " " ins.mout " = " mt.mix "(" ins.mb ", " ins.ma ", "
                                       (call (weight-name ins.desc) (.. ins.da ", " ins.db) ins.args)
                                       ");"))))
    :cells (let [c (.. "c" (ins.dout:sub 2))
                 body []]
             (table.insert out (.. "float " ins.dout " = 10000000000.0;"))
             (when materials? (table.insert out (.. mt.type " " ins.mout " = " mt.zero ";")))
             (table.insert out (.. "for (int " c " = 0; " c " < " ins.count "; " c "++) {"))
             ;; The cell index is the last argument.
             (table.insert body (.. "vec3 " ins.cell-p " = "
                                    (call ins.desc.glsl-name (reg ins.pin) ins.args c) ";"))
             (emit-code body ins.body materials?)
             (if materials?
                 (table.insert body (.. "if (" ins.body-d " < " ins.dout ") { " ins.dout " = "
                                        ins.body-d "; " ins.mout " = " ins.body-m "; }"))
                 (table.insert body (.. ins.dout " = min(" ins.dout ", " ins.body-d ");")))
             (each [_ l (ipairs body)] (table.insert out (.. "    " l)))
             (table.insert out "}"))
    _ (error (.. "emit-glsl: unknown instruction " (tostring ins.op)))))

(set emit-code
     (fn [out code materials?]
       (each [_ ins (ipairs code)] (emit-instr out ins materials?))
       out))

(fn text-lines [text]
  "The lines of `text`."
  (icollect [line (: (.. text "\n") :gmatch "([^\n]*)\n")] line))

(fn functions [tape ?defined]
  "GLSL definitions of every helper and function the tape uses, in first-use order,
but those named in `?defined` (GLSL name -> true: already in the shader)."
  (let [out []
        defined (or ?defined {})]
    (each [_ u (ipairs tape.used)]
      (when (u.name:find "^helper:")
        (table.insert out (. primitives.helpers u.desc))))
    (each [_ u (ipairs tape.used)]
      (when (and (not (u.name:find "^helper:")) (not (. defined u.name)))
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

(fn declarations [tape]
  "The parameter array's declaration (nothing for an empty tape)."
  (if (> (length tape.rows) 0)
      [(.. "uniform vec4 uTape[" (length tape.rows) "];  // tree parameters and materials")]
      []))

(fn object-comment [o]
  (.. "// " o.info.path ": " o.info.kind))

(fn indented [lines]
  (icollect [_ l (ipairs lines)] (.. "    " l)))

(fn guarded-lines [o materials? tail]
  "Lines of object `o`'s code, then the lines `tail` (which use its distance). With a
guard (see src/sdf/lower.fnl), the code after the guard's box and `tail` run only
where that box is nearer than d: elsewhere the object's value, at least the box's,
could not lower d."
  (if o.guard
      (let [head (emit-code [] (fcollect [i 1 o.guard.head] (. o.code i)) materials?)
            rest (emit-code [] (fcollect [i (+ o.guard.head 1) (length o.code)] (. o.code i))
                            materials?)]
        (table.insert head (.. "if (" o.guard.bout " < d) {"))
        (each [_ l (ipairs (indented rest))] (table.insert head l))
        (each [_ l (ipairs (indented tail))] (table.insert head l))
        (table.insert head "}")
        head)
      (let [lines (emit-code [] o.code materials?)]
        (each [_ l (ipairs tail)] (table.insert lines l))
        lines)))

(fn distance-terms [tape ?first-id]
  "Lines for map(): each tree object's distance, folded into d. With `?first-id`, for
mapOthers(): each but the one gObject numbers (see color-terms)."
  (icollect [i o (ipairs tape.objects)]
    [(object-comment o)
     (if ?first-id (.. "if (gObject != " (+ ?first-id i -1) ") {") "{")
     (indented (guarded-lines o false [(.. "d = min(d, " o.dout ");")]))
     "}"]))

(fn color-terms [tape mirrors? ?first-id]
  "Lines for mapColor(): as map(), keeping the nearest object's colour in `color` (and
its mirror amount in gMirror when `mirrors?`; with two-row materials, always, and
the second row in gMaterial). With `?first-id`, also its number in gObject: the
tree objects are numbered from it in tape order (see object-terms)."
  (set mt (. material-types tape.material-size))
  (let [modern? (= tape.material-size 8)]
    (icollect [i o (ipairs tape.objects)]
      (let [row (if modern? (.. o.mout "[0]") o.mout)]
        [(object-comment o) "{"
         (indented
          (guarded-lines
           o true
           [(.. "if (" o.dout " < d) { d = " o.dout "; color = " row ".rgb;"
                (if (or mirrors? modern?) (.. " gMirror = " row ".a;") "")
                (if modern? (.. " gMaterial = " o.mout "[1];") "")
                (if ?first-id (.. " gObject = " (+ ?first-id i -1) ";") "") " }")]))
         "}"]))))

(fn object-terms [tape first-id]
  "Lines for mapObject(): each tree object's distance alone, returned when gObject
holds its number (numbered from `first-id` in tape order, as color-terms does)."
  (icollect [i o (ipairs tape.objects)]
    [(.. "if (gObject == " (+ first-id i -1) ") {  " (object-comment o))
     (icollect [_ l (ipairs (emit-code [] o.code false))] (.. "    " l))
     (.. "    return " o.dout ";")
     "}"]))

{: functions : declarations : distance-terms : color-terms : object-terms : text-lines
 : float-literal}
