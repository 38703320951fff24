;; The tape interpreter (issue 42): a scene's tape (src/sdf/lower.fnl) as a program
;; that one shader reads from a texture, so a structural edit needs no compile when
;; the shader already holds the functions the new tape calls. The third evaluator of
;; the tape, beside the GLSL (emit-glsl.fnl) and Lua (emit-lua.fnl) emitters; the
;; shader's side is written here too, from the same descriptors, so the two agree on
;; every opcode.
;;
;; The instruction set of a tape is what its instructions call: each (role, GLSL
;; function) pair, and the exact gradients of its leaves; sorted, it numbers the
;; opcodes, and it is the interpreter shader's key: a tape whose set the shader holds
;; runs on it as it is. A few opcodes are the tape's own (far field, Lipschitz
;; division, material, the end of a repetition).
;;
;; The program is a list of floats, four to a texel of an rgba32f image (uProgram,
;; `width` texels to a line):
;;   texel 0           (objects, 0, 0, 0)
;;   texel 1 + 3k      object k's (pc, end, guard pc or -1, gradient pc or -1)
;;   texel 2 + 3k      its (distance register, material register, guard's box
;;                     register, gradient end)
;;   texel 3 + 3k      (1 for a half-space, met in closed form by a bounded march
;;                     (tapePlanesHit), else 0; 0, 0, 0)
;;   then the code: an instruction is two texels, (op, r0, r1, r2) and (r3, r4, r5,
;;   texels it takes), then its arguments two to a texel: (index, index read as an
;;   estimate, ...), each an index of a float in the tape's rows (row * 4 + offset),
;;   which the shader reads from the rows' own texture (uTape) as the player sends it.
;; Registers are numbered per kind (distances, points, materials), reused once dead;
;; point register 0 is the point the object is evaluated at.

(local primitives (require :src.sdf.primitives))
;; `pairs` under another name: a loop over `pairs` by that name is LuaJIT's ITERN,
;; which Debian 12's LuaJIT ends early once despecialised (see src/util/wire.fnl).
(local each-pair pairs)
(local operations (require :src.sdf.operations))
(local large-sphere (require :src.sdf.large-sphere))

;; Registers of each kind an object may use; nesting of repetitions.
(local max-registers 32)
(local max-depth 4)
;; Texels to a line of the program's image.
(local width 1024)
;; The tape's own opcodes; a function's are `first-function` on, in set order.
(local ops {:far 1 :divide 2 :material 3 :cells-end 4})
(local first-function 8)

(fn each-instruction [code f]
  (each [_ ins (ipairs code)]
    (f ins)
    (when ins.body (each-instruction ins.body f))
    (when ins.near? (each-instruction ins.near?.code f))))

(local {: gradient-name} (require :src.sdf.emit-glsl))

(fn entry-key [role desc]
  (.. role ":" (if (= role :gradient) (gradient-name desc) desc.glsl-name)))

(fn members-of [tape]
  "The objects the program runs, in tape order (their object numbers): each tape
object, an instance group's members one each, each {:o tape-object :shift rows}: its
code reads rows `shift` further on in the interpreter's rows (the tape's, then the
instance bank's)."
  (let [out []
        tape-rows (length tape.rows)]
    (each [_ o (ipairs tape.objects)]
      (if o.instances
          (for [j 0 (- o.instances.count 1)]
            (table.insert out {: o :shift (+ tape-rows o.instances.base (* j o.instances.stride))}))
          (table.insert out {: o :shift 0})))
    out))

;; Objects a program may hold: each pixel's every step visits all of them.
(local max-objects 1024)

(fn refusal [tape]
  "Why `tape` cannot run on the interpreter, or nil when it can: every object a tree
or an instance group's member (not a field), at most max-objects of them, no blend
(a union of many children of one structure), no folded value."
  (var why nil)
  (each [_ o (ipairs tape.objects) &until why]
    (if (and (not= o.strategy :tree) (not= o.strategy :group))
        (set why (.. "objects drawn as " (tostring o.strategy)))
        (?. o :instances :texture?) (set why "an instance group read from a texture")
        (each-instruction o.code
                          (fn [ins]
                            (when (not why)
                              (set why (if (= ins.op :blend) "a union of many children of one structure"
                                           ins.literal "values folded into the code"
                                           (accumulate [lit nil _ a (ipairs (or ins.args [])) &until lit]
                                             (when a.literal "values folded into the code")))))))))
  (let [n (length (members-of tape))]
    (when (and (not why) (> n max-objects))
      (set why (string.format "%d objects (at most %d: every step of every pixel visits each)"
                              n max-objects))))
  ;; Repetitions inside repetitions: the shader's loop stack holds max-depth.
  (fn depth [code]
    (accumulate [most 0 _ ins (ipairs code)]
      (math.max most (if ins.body (+ 1 (depth ins.body)) 0))))
  (each [_ o (ipairs tape.objects) &until why]
    (when (> (depth (or o.code [])) max-depth)
      (set why (.. "repetitions nested more than " max-depth " deep"))))
  why)

(fn instruction-set [tape ?base]
  "The instruction set `tape` calls (see the top of this file): a sorted list of
{:key :role :desc}, with those of `?base` (another set) added."
  (let [seen {}
        out []]
    (fn add [role desc args]
      (let [key (entry-key role desc)]
        (when (not (. seen key))
          (tset seen key true)
          ;; The arguments' types and estimates (a post step takes its operation's).
          (table.insert out {: key : role : desc
                             :args (icollect [_ a (ipairs args)] {:type a.type :estimate? a.estimate?})}))))
    (each [_ e (ipairs (or ?base []))] (add e.role e.desc e.args))
    (each [_ o (ipairs tape.objects)]
      (each-instruction (or o.code [])
                        (fn [ins]
                          (when (and ins.desc (not= ins.op :blend)) (add ins.op ins.desc ins.args))))
      (let [prim (?. o :leaf :prim)]
        (when (and prim prim.desc.gradient-glsl) (add :gradient prim.desc prim.args))))
    (doto out (table.sort (fn [a b] (< a.key b.key))))))

(fn catalogue []
  "An instruction set of every primitive (and its exact gradient), every operation in
its general form and its kernels (:variants), with their post steps: what the
player's interpreter holds besides a scene's own, so that an edit to another kind
needs no compile. Forms an operation takes for particular values (a repetition along
some axes, a rotation that permutes them, a plane facing up) are not in it: a tape
that calls one adds it (instruction-set)."
  (let [out []]
    (each [_ d (ipairs (doto (icollect [_ d (ipairs primitives.all)] d)
                         (table.insert large-sphere.descriptor)))]
      (table.insert out {:role :prim :desc d :args d.args})
      (when d.gradient-glsl (table.insert out {:role :gradient :desc d :args d.args})))
    (each [_ d (ipairs operations.all)]
      (each [_ form (ipairs (if d.variants (icollect [_ v (each-pair d.variants)] v) [d]))]
        (let [args (if form.args form.args d.args)]
          (table.insert out {:role d.role :desc form : args})
          (when d.post (table.insert out {:role :post :desc d.post : args})))))
    (instruction-set {:objects []} out)))

(fn set-key [iset]
  "A text naming instruction set `set`: equal texts, the same shader."
  (table.concat (icollect [_ e (ipairs iset)] e.key) " "))

(fn opcodes [iset]
  (collect [i e (ipairs iset)] e.key (+ first-function i -1)))

;;; Registers: a linear scan over the object's code, repetitions' bodies in line.

(fn register-kind [name]
  ;; d distances (b a guard's box distance, a distance too), p points, m materials.
  (case (name:sub 1 1) "b" "d" k k))

(fn instruction-registers [ins]
  ;; What `ins` reads and writes, by register name.
  (case ins.op
    :prim {:reads [ins.pin] :writes [ins.dout]}
    :point {:reads [ins.pin] :writes [ins.pout]}
    :post {:reads [ins.din ins.pin] :writes [ins.dout]}
    :distance {:reads [ins.din ins.pin] :writes [ins.dout]}
    :combine {:reads [ins.da ins.db ins.ma ins.mb] :writes [ins.dout ins.mout]}
    :far {:reads [ins.din ins.bin] :writes [ins.dout]}
    :divide {:reads [ins.din] :writes [ins.dout]}
    :material {:reads [] :writes [ins.mout]}
    :gradient {:reads [ins.pin] :writes []}
    _ {:reads [] :writes []}))

(fn linear [code]
  ;; The code as steps in order: each instruction, a repetition as its start (which
  ;; writes its cell's point and its outputs), its body, then its end (which reads the
  ;; body's values). Also each repetition's span of steps.
  (let [steps []
        loops []]
    (fn walk [code]
      (each [_ ins (ipairs code)]
        (if (= ins.op :cells)
            (let [start (+ 1 (length steps))
                  near ins.near?]
              (table.insert steps {: ins :reads [ins.pin] :writes [ins.cell-p ins.dout ins.mout]})
              (walk ins.body)
              (table.insert steps {:end ins :reads [ins.body-d ins.body-m ins.pin ins.cell-p]
                                   :writes [ins.dout ins.mout]})
              (table.insert loops {: start :finish (length steps)})
              ;; The neighbours drawn by their boxes: a second loop, from cell 1.
              (when near
                (let [start (+ 1 (length steps))]
                  (table.insert steps {: ins :reads [ins.pin ins.dout ins.cell-p] :writes [near.p]})
                  (walk near.code)
                  (table.insert steps {:end ins :reads [near.bout near.p ins.cell-p ins.dout ins.pin]
                                       :writes [ins.dout]})
                  (table.insert loops {: start :finish (length steps)}))))
            (table.insert steps (doto (instruction-registers ins) (tset :ins ins))))))
    (walk code)
    (values steps loops)))

(fn allocate [code outputs]
  "Register numbers for the names `code` uses (name -> number, and the count of each
kind), live ranges from a linear scan: a name read inside a repetition but written
before it lives to the repetition's end (the body runs again); `outputs` (names)
live to the end. nil and a message when a kind needs more than max-registers."
  (let [(steps loops) (linear code)
        first {}
        last {}]
    (each [i s (ipairs steps)]
      (each [_ n (ipairs s.writes)] (when (and n (not (. first n))) (tset first n i)))
      (each [_ n (ipairs s.reads)]
        (when n
          (var at i)
          (each [_ l (ipairs loops)]
            (when (and (<= l.start i l.finish) (< (or (. first n) 0) l.start))
              (set at (math.max at l.finish))))
          (tset last n (math.max at (or (. last n) 0))))))
    (each [_ n (ipairs outputs)] (when n (tset last n math.huge)))
    (let [numbers {:p0 0}
          free {:d [] :p [] :m []}
          counts {:d 0 :p 1 :m 0}
          live []]
      (var err nil)
      (each [i s (ipairs steps) &until err]
        ;; Free what died before this step (not what dies at it: a step reads its
        ;; inputs after writing a first output).
        (for [k (length live) 1 -1]
          (let [n (. live k)]
            (when (< (or (. last n) (. first n)) i)
              (table.insert (. free (register-kind n)) (. numbers n))
              (table.remove live k))))
        (each [_ n (ipairs s.writes)]
          (when (and n (not (. numbers n)))
            (let [kind (register-kind n)
                  pool (. free kind)]
              (table.sort pool (fn [a b] (> a b)))
              (tset numbers n (or (table.remove pool)
                                  (let [c (. counts kind)]
                                    (tset counts kind (+ c 1))
                                    c)))
              (when (>= (. numbers n) max-registers)
                (set err (.. "an object needs more than " max-registers " registers of a kind")))
              (table.insert live n)))))
      (if err (values nil err) (values numbers counts)))))

;;; The program.

(fn visible-args [args]
  ;; The arguments a call passes, each {:main ref :alt ref}: an argument marked
  ;; :estimate? is the one before it as read where the field is an estimate.
  (let [out []]
    (each [i a (ipairs args)]
      (when (not a.estimate?)
        (let [nxt (. args (+ i 1))]
          (table.insert out {:main a :alt (if (?. nxt :estimate?) nxt a)}))))
    out))


(fn program [tape iset]
  "The program of `tape` for instruction set `set` (see the top of this file):
{:data [floats] :width :height :objects n :registers {:d :p :m}}, or nil and a
message (the tape calls what the set lacks, an object needs too many registers)."
  (let [codes (opcodes iset)
        header []
        body []
        members (members-of tape)
        base (+ 1 (* 3 (length members)))
        most {:d 1 :p 1 :m 1}
        allocated {}]
    (var err (refusal tape))
    ;; Rows the member being emitted reads its arguments at (members-of).
    (var shift 0)
    (fn index-of [ref] (+ (* 4 (+ shift ref.row)) ref.offset))
    (fn texel [out a b c d] (each [_ v (ipairs [a b c d])] (table.insert out v)))
    (fn pc [] (+ base (/ (length body) 4)))
    (fn emit [numbers ins]
      (let [r #(if $ (. numbers $) -1)
            op (if (. ops ins.op) (. ops ins.op)
                   (. codes (entry-key ins.op ins.desc)))
            args (visible-args (or ins.args []))
            texels (+ 2 (math.ceil (/ (length args) 2)))]
        (if (not op) (set err (.. "the interpreter lacks " (entry-key ins.op ins.desc)))
            (do
              (case ins.op
                :prim (do (texel body op (r ins.dout) (r ins.pin) -1) (texel body -1 -1 -1 texels))
                :point (do (texel body op (r ins.pout) (r ins.pin) -1) (texel body -1 -1 -1 texels))
                :post (do (texel body op (r ins.dout) (r ins.din) (r ins.pin)) (texel body -1 -1 -1 texels))
                :distance (do (texel body op (r ins.dout) (r ins.din) (r ins.pin))
                              (texel body -1 -1 -1 texels))
                :combine (do (texel body op (r ins.dout) (r ins.da) (r ins.db))
                             (texel body (r ins.mout) (r ins.ma) (r ins.mb) texels))
                :far (do (texel body op (r ins.dout) (r ins.din) (r ins.bin)) (texel body -1 -1 -1 2))
                :divide (do (texel body op (r ins.dout) (r ins.din) -1) (texel body (/ 1 ins.k) -1 -1 2))
                :material (let [at (* 4 (+ shift ins.row))]
                            (texel body op (r ins.mout) -1 -1) (texel body -1 -1 -1 3)
                            (texel body at at -1 -1))
                :gradient (do (texel body op -1 (r ins.pin) -1) (texel body -1 -1 -1 texels))
                ;; A loop's first cell and count; a loop from cell 1 (a near
                ;; repetition's neighbours) keeps the value the first one left.
                :cells (let [first (or ins.first-cell 0)
                             count (if ins.near? (if (= first 0) 1 ins.count) ins.count)]
                         (texel body op (r ins.dout) (r ins.pin) (r (if (= first 0) ins.cell-p ins.near?.p)))
                         (texel body (r ins.mout) first count texels)))
              (when (not= ins.op :material)
                (for [i 1 (length args) 2]
                  (let [a (. args i) b (. args (+ i 1))]
                    (texel body (index-of a.main) (index-of a.alt)
                           (if b (index-of b.main) -1) (if b (index-of b.alt) -1)))))))))
    (fn emit-code [numbers code]
      (each [_ ins (ipairs code) &until err]
        (if (= ins.op :cells)
            (let [start (pc)
                  near ins.near?]
              (emit numbers ins)
              (emit-code numbers ins.body)
              (texel body ops.cells-end (. numbers ins.body-d) (. numbers ins.dout) start)
              (texel body (. numbers ins.body-m) (. numbers ins.mout) 0 2)
              ;; Near: each neighbour's copy by its box, but where a neighbour is the
              ;; own cell (clamped past a limited repetition's end).
              (when near
                (let [start (pc)]
                  (emit numbers (doto (collect [k v (each-pair ins)] k v) (tset :first-cell 1)))
                  (emit-code numbers near.code)
                  (texel body ops.cells-end (. numbers near.bout) (. numbers ins.dout) start)
                  (texel body (. numbers near.p) (. numbers ins.cell-p) 1 2))))
            (emit numbers ins))))
    (fn note-counts [counts]
      (each [k n (each-pair counts)] (tset most k (math.max (. most k) n))))
    (texel header (length members) 0 0 0)
    (local table-rows [])
    (each [_ m (ipairs members) &until err]
      (set shift m.shift)
      (let [o m.o
            outputs [o.dout o.mout (?. o :guard :bout)]
            ;; A group's members share their code, and so its registers.
            (numbers counts) (case (. allocated o)
                               a (values (. a 1) (. a 2))
                               _ (let [(n c) (allocate o.code outputs)]
                                   (tset allocated o [n c])
                                   (values n c)))]
        (if (not numbers) (set err counts)
            (let [start (pc)]
              (var guard-pc -1)
              (note-counts counts)
              (each [i ins (ipairs o.code) &until err]
                (when (and o.guard (= i (+ o.guard.head 1))) (set guard-pc (pc)))
                (if (= ins.op :cells) (emit-code numbers [ins]) (emit numbers ins)))
              (when (and o.guard (= guard-pc -1)) (set guard-pc (pc)))
              (let [finish (pc)
                    prim (?. o :leaf :prim)
                    gradient (when (and prim prim.desc.gradient-glsl (not err))
                               (let [code (doto (icollect [_ p (ipairs o.leaf.points)] p)
                                            (table.insert {:op :gradient :desc prim.desc
                                                           :args prim.args :pin prim.pin}))
                                     (gnumbers gcounts) (allocate code [])]
                                 ;; (A group's members each have their own copy.)
                                 (if (not gnumbers) (do (set err gcounts) nil)
                                     (let [at (pc)]
                                       (note-counts gcounts)
                                       (each [_ ins (ipairs code)] (emit gnumbers ins))
                                       [at (pc)]))))]
                (table.insert table-rows [[start finish guard-pc (if gradient (. gradient 1) -1)]
                                          [(. numbers o.dout) (or (. numbers o.mout) -1)
                                           (if o.guard (. numbers o.guard.bout) -1)
                                           (if gradient (. gradient 2) -1)]
                                          [(if o.half-space? 1 0) 0 0 0]]))))))
    (if err (values nil err)
        (let [data header]
          (each [_ [a b c] (ipairs table-rows)]
            (texel data (unpack a))
            (texel data (unpack b))
            (texel data (unpack c)))
          (each [_ v (ipairs body)] (table.insert data v))
          (let [texels (/ (length data) 4)]
            {: data :width (math.min texels width) :height (math.ceil (/ texels width))
             :objects (length members) :registers most})))))

;;; The shader's side.

(local arg-readers {:float "tapeFloat" :vec2 "tapeVec2" :vec3 "tapeVec3" :vec4 "tapeVec4"})

(fn call-args [args]
  ;; The argument reads of a call taking `args`, by the instruction at pc.
  (let [out []]
    (var k 0)
    (each [_ a (ipairs args)]
      (when (not a.estimate?)
        (table.insert out (.. (. arg-readers a.type) "(pc, " k ")"))
        (set k (+ k 1))))
    out))

(fn case-lines [e code material-mix]
  ;; The switch's case for set entry `e`, opcode `code`.
  (let [desc e.desc
        args (call-args e.args)
        with #(table.concat [$1 (unpack args)] ", ")
        body (case e.role
               :prim [(.. "gTapeD[r0] = " desc.glsl-name "(" (with "gTapeP[r1]") ");")]
               :point [(.. "gTapeP[r0] = " desc.glsl-name "(" (with "gTapeP[r1]") ");")]
               :post [(.. "gTapeD[r0] = " desc.glsl-name "(" (with "gTapeD[r1], gTapeP[r2]") ");")]
               :distance [(.. "gTapeD[r0] = " desc.glsl-name "(" (with "gTapeD[r1], gTapeP[r2]") ");")]
               :combine (let [w (.. "w" (desc.glsl-name:sub 3))]
                          [(.. "float a = gTapeD[r1], b = gTapeD[r2];")
                           (.. "gTapeD[r0] = " desc.glsl-name "(" (with "a, b") ");")
                           (.. "if (materials) gTapeM[int(t.x)] = " material-mix "(gTapeM[int(t.z)], "
                               "gTapeM[int(t.y)], " w "(" (with "a, b") "));")])
               :gradient [(.. "gTapeGradient = " (gradient-name desc) "(" (with "gTapeP[r1]") ");")]
               :cells ["if (depth == 0 || loopStart[depth - 1] != pc) {"
                       "    loopStart[depth] = pc;"
                       "    loopCell[depth] = int(t.y);"
                       "    depth++;"
                       "    // From cell 1 (a near repetition's neighbours) the value stays."
                       "    if (t.y < 0.5) {"
                       "        gTapeD[r0] = 10000000000.0;"
                       "        if (materials) gTapeM[int(t.x)] = kTapeNoMaterial;"
                       "    }"
                       "}"
                       (.. "gTapeP[r2] = " desc.glsl-name "(" (with "gTapeP[r1]")
                           ", loopCell[depth - 1]);")])]
    (doto (icollect [_ l (ipairs body)] (.. "    " l))
      (table.insert 1 (.. "case " code ": {  // " e.key))
      (table.insert "    break;")
      (table.insert "}"))))

(fn shader-slots [iset material-size]
  "What the interpreter's chunk (shaders/strategies/interpreted.glsl) is filled with
for instruction set `iset` (the functions it calls already written before it): its
switch's cases, one per function; the opcodes of the tape's own instructions; the
material type (vec4, or mat2x4 with `material-size` 8) and how a material is read;
the sizes of the registers (max-registers of each kind, so every program of the set
runs on it), of the loop stack and of a line of the program's texture."
  (let [modern? (= material-size 8)
        codes (opcodes iset)
        cases []]
    (each [_ e (ipairs iset)]
      (each [_ l (ipairs (case-lines e (. codes e.key) (if modern? "mixMaterial" "mix")))]
        (table.insert cases l)))
    {:cases cases
     :functions (tostring (length iset))
     :width (tostring width)
     :registers (tostring max-registers)
     :depth (tostring max-depth)
     :far (tostring ops.far) :divide (tostring ops.divide) :material (tostring ops.material)
     :cells-end (tostring ops.cells-end)
     :material-type (if modern? "mat2x4" "vec4")
     :material-zero (if modern? "mat2x4(0.0)" "vec4(0.0)")
     :material-read [(if modern?
                         "gTapeM[r0] = mat2x4(tapeRowAt(row), tapeRowAt(row + 4));"
                         "gTapeM[r0] = tapeRowAt(row);")]}))

(fn tape-of [tape ?base]
  "`tape` drawn by the interpreter: a tape of one object, of strategy :interpreted
(src/sdf/strategies/interpreted.fnl), that holds `tape` (:tape), its instruction set
with `?base`'s (:set) and its program (:program); no rows of its own (the
interpreter reads `tape`'s from their texture). Its key names the set alone: any
tape of that set draws with the same shader. A field (`tape`'s first object when
it has one) stays before it, as it is (program-object finds the interpreted one).
nil and why when `tape` cannot run on the interpreter."
  (let [;; A field (the first object when the scene has one: lower.fnl) keeps its
        ;; own strategy: its members are data in its textures, walked through its
        ;; grid (what the interpreter would visit one by one at every step). Its
        ;; count is read from a uniform (:count-read?), so the text does not hold it.
        field (let [o (. tape.objects 1)]
                (when (and o (= o.strategy :field))
                  (collect [k v (each-pair o) &into {:count-read? true}] k v)))
        tape (if field
                 (collect [k v (each-pair tape) &into {:objects (icollect [i o (ipairs tape.objects)]
                                                              (when (> i 1) o))}]
                   (when (not= k :objects) (values k v)))
                 tape)]
    (case (refusal tape)
      why (values nil why)
      _ (let [iset (instruction-set tape ?base)
              (prog err) (program tape iset)
              used {}]
          (if (not prog) (values nil err)
              {:objects (doto (if field [field] [])
                          (table.insert {:strategy :interpreted :tape tape
                                         ;; Numbered after the field's members
                                         ;; (a uniform's count in the text).
                                         :id (if field field.field.count 0)
                                         :after-field? (not= nil field)
                                         :set iset :program prog
                                         :info {:kind :interpreted :path "interpreted"
                                                :implicit? true :children []}}))
               ;; No object is written in the code (:count, codegen's comment): the text
               ;; depends on the set alone (and a field's kinds: the plan's key).
               :count 0 :rows [] :relative [] :inner [] :derived [] :blends []
               :instances {:rows [] :relative [] :inner [] :derived []}
               :mirrors? tape.mirrors? :estimates? tape.estimates?
               :material-size tape.material-size
               ;; The functions the set calls, each once (what emit-glsl writes).
               :used (icollect [_ e (ipairs iset)]
                       (when (and (not= e.role :gradient) (not (. used e.desc.glsl-name)))
                         (tset used e.desc.glsl-name true)
                         {:name e.desc.glsl-name :desc e.desc}))
               :key (.. "interpreted " (set-key iset) " materials:" tape.material-size
                        (if tape.estimates? " estimates" ""))})))))

;; Mesa's llvmpipe ends every loop of a shader invocation once 65,535 turns of all its
;; loops together have run (LP_MAX_TGSI_LOOP_ITERATIONS in gallivm/lp_bld_limits.h: one
;; counter for the whole shader, since every call is inlined). The interpreter's loop
;; turns once per instruction, for every object at every distance a pixel asks for, so
;; a program of many objects is cut short there: rays that take many steps (near
;; silhouettes) end on a wrong distance (black specks), where a GPU draws it right.
;; Measured on test/fixtures/grid-modern.fnl's kind of scene (rotated round boxes and
;; tori, soft shadows, occlusion; the GPU against the CPU reference, 512 pixels): 41
;; objects (282 turns a distance) drew clean, 101 (702) put 3 pixels over the budget,
;; 201 (1,402) 150. So on a software renderer the interpreter takes a program of at
;; most 300 turns a distance (65,535 turns cover 218 distances a pixel then), shared
;; by a still's rays (one loop): organic (66 turns) drew its 4 x 4 adaptive still with
;; 828 of 5,184 pixels wrong, its one-ray picture with none. Every scene of scenes/
;; takes 111 or fewer.
(local software-turns 300)

(fn code-turns [code]
  ;; The interpreter's loop turns for `code` once: an instruction each, a
  ;; repetition's body once per cell (and its neighbours' copies), its end each time.
  (accumulate [n 0 _ ins (ipairs code)]
    (+ n (if (= ins.op :cells)
             (let [cells (or ins.count 1)]
               (+ 1 (* cells (+ 1 (code-turns ins.body)))
                  (if ins.near? (* cells (+ 1 (code-turns ins.near?.code))) 0)))
             1))))

(fn loop-turns [tape]
  "The tape interpreter's loop turns for one distance of `tape` (every object's
instructions, a repetition's body once per cell): see software-fits?."
  (accumulate [n 0 _ m (ipairs (members-of tape))]
    (+ n (code-turns (or m.o.code [])))))

(fn software-fits? [tape ?rays]
  "Whether the interpreter draws `tape` right on a software renderer (llvmpipe),
whose loops all stop after 65,535 turns in a shader, with `?rays` rays a pixel (1; a
still's more, in one loop): true, or false, the turns one distance takes, and the
most that fit (software-turns over the rays)."
  (let [turns (loop-turns tape)
        most (math.floor (/ software-turns (or ?rays 1)))]
    (if (<= turns most) true (values false turns most))))

(fn program-object [tape]
  "The object of `tape` (as tape-of gives it) that the interpreter runs: its last,
after a field."
  (. tape.objects (length tape.objects)))

{: refusal : instruction-set : catalogue : tape-of : program-object : set-key : program : shader-slots
 : members-of : max-objects : max-registers : width : ops : first-function
 : loop-turns : software-fits?}
