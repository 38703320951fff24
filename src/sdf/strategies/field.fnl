;; The field strategy: many of the article's flat spheres and boxes (and marched
;; primitives) drawn from a grid in textures that a ray walks (src/render/field.fnl,
;; shaders/pipeline/field.glsl), the first tape object (lower.fnl's field-object). Its
;; members are numbered from 0 by the field's functions; `first` + o.id is the
;; number of its first. See src/sdf/strategies.fnl for the interface.

(local glsl (require :src.sdf.emit-glsl))
(local chunks (require :src.render.chunks))
(local field (require :src.render.field))
(local lower (require :src.sdf.lower))
(local runs (require :src.reference.distance))
(local primitives (require :src.sdf.primitives))
(local bounds (require :src.render.bounds))
(local box-gradient (. (primitives.lookup :box) :gradient))

(fn field-number [expr first]
  ;; A member's number `expr` (from 0) as an object's number.
  (if (= first 0) expr (.. expr " + " first)))

(fn field-index [first ?var]
  ;; gObject (or the int `?var`) as the number of a member (from 0).
  (let [v (or ?var "gObject")]
    (if (= first 0) v (.. v " - " first))))

(fn field-selected [o first action ?var]
  ;; `action` (a GLSL expression's prefix) on member gObject (or `?var`) when it is
  ;; the field's.
  (let [id (+ first o.id)
        v (or ?var "gObject")
        ;; Its count written, or read (the interpreter's: interpret.tape-of).
        past (if (not o.count-read?) (+ id o.field.count)
                 (= id 0) "uFieldCount"
                 (.. id " + uFieldCount"))]
    [(.. "if (" v " >= " id " && " v " < " past ") " action "(p, "
         (field-index id v) ");")]))

(local chunk "shaders/strategies/field.glsl")

(fn field-minimum [skip]
  ;; The field's part of a minimum, skipping its member `skip` (a GLSL int).
  (chunks.fill-part chunk :minimum {: skip}))

(fn color-lines [o ?first]
  ;; mapColor's term: the nearest member's colour (and with ?first its number).
  (chunks.fill-part chunk :color
                    {:object (if ?first
                                 [(.. "gObject = best >= 0 ? " (field-number "best" (+ ?first o.id))
                                      " : -1;")]
                                 [])}))

(fn exact? [o]
  ;; Spheres and boxes only: their round boxes have their inner box's normal; with
  ;; marched members, differences are taken for all of them.
  (= 0 (length o.field.kinds.marched)))

(fn evaluators [tape o what into]
  ;; The members' CPU evaluators by object number: each its shape's round box, by the
  ;; descriptor's CPU form, or a marched member's own primitive in its frame; matte
  ;; (the shader's field keeps the mirror amount and material mapColor starts from).
  ;; A round box's exact normal is its inner box's gradient, except in a field with
  ;; marched members (exact?).
  (let [f o.field
        what (if (= what :estimate) :distance what)
        round-box f.desc.cpu
        modern? (= tape.material-size 8)
        exact? (exact? o)]
    (each [_ m (ipairs f.members)]
      (let [(cx cy cz hx hy hz r) (lower.field-shape m)
            marched (when m.tree (lower.field-marched m))
            distance (if marched (fn [x y z] (field.marched-distance marched x y z cx cy cz))
                         (fn [x y z] (round-box (- x cx) (- y cy) (- z cz) hx hy hz r)))]
        (table.insert into
                      (case what
                        :distance distance
                        :material (let [[cr cg cb] (if marched marched.color m.color)]
                                    (if modern?
                                        (fn [x y z] (values (distance x y z) cr cg cb 0 0.5 0 0 0))
                                        (fn [x y z] (values (distance x y z) cr cg cb 1))))
                        :gradient (if (not exact?) false
                                      (fn [x y z] (box-gradient (- x cx) (- y cy) (- z cz) hx hy hz)))))))))

(fn marched-args [desc]
  ;; The GLSL arguments of marched primitive `desc` after the point, read from its
  ;; packed numbers in the vectors u and v (field-primitives.glsl's fieldKindDistance).
  (let [component (fn [i] (.. (if (< i 4) "u." "v.") (string.sub "xyzw" (+ 1 (% i 4)) (+ 1 (% i 4)))))
        out []]
    (var at 0)
    (each [_ a (ipairs desc.args)]
      (let [n (. primitives.glsl-types a.type)
            parts (fcollect [i at (+ at n -1)] (component i))]
        (table.insert out
                      (if (= n 1) (. parts 1)
                          ;; (a swizzle when the components lie in one vector)
                          (= (math.floor (/ at 4)) (math.floor (/ (+ at n -1) 4)))
                          (.. (string.sub (. parts 1) 1 2)
                              (table.concat (icollect [_ p (ipairs parts)] (string.sub p 3))))
                          (.. a.type "(" (table.concat parts ", ") ")")))
        (set at (+ at n))))
    (table.concat out ", ")))

(fn field-lines [plan fill]
  ;; The field's functions (shaders/pipeline/field.glsl, filled by the chunk system's
  ;; `fill`) with the code of the kinds it holds, and its marched members'
  ;; (field-primitives.glsl) when it has some.
  (let [{: spheres? : boxes? : marched} plan.field.kinds
        marched? (> (length marched) 0)
        record-b "fieldRead(uFieldRecords, uFieldRows.y, r + 1)"
        box (.. "fieldBoxEntry(q0, inv, a, " (if marched? "b" record-b) ".xyz)")
        closed (if (and spheres? boxes?) (.. "a.w > 0.0 ? fieldSphereEntry(q0, rd, a) : " box)
                   spheres? "fieldSphereEntry(q0, rd, a)"
                   boxes? box)
        march "fieldMarchedEntry(q0, rd, a, int(-b.x), int(b.w), t0)"]
    [;; Finite objects beside the field (mapFinite): counted in the code, or as many
     ;; as the bounds' image holds (the interpreter's: boundsCount, defined after
     ;; this, where the march reads it).
     (if (?. plan.tape.objects 1 :count-read?)
         "uniform int uFieldCount;  // its members (the interpreter's: not in the text)"
         [])
     (.. "#define fieldOthers() "
         (if plan.bounds.texture? "(boundsCount() > 0)" (tostring (bounds.others? plan)))
         "  // finite objects beside the field (mapFinite)")
     (string.format "const float kFieldTiny = %.6f;  // a ray direction's smallest component"
                    field.tiny)
     (.. "const int kFieldObjectTexels = " (field.object-texels plan.field)
         ";  // texels per object in uFieldObjects")
     (if marched?
         [(.. "const int kFieldMarchTurns = " field.marched-turns
              ";  // steps a ray may take in a marched member")
          (.. "const int kFieldArgTexels = " (field.arg-texels plan.field)
              ";  // texels of a marched member's numbers")]
         [])
     (fill "shaders/pipeline/field.glsl"
           {:marched (if marched?
                         (fill "shaders/pipeline/field-primitives.glsl"
                               {:kinds (icollect [k name (ipairs marched)]
                                         (let [desc (primitives.lookup name)
                                               call (.. "return " desc.glsl-name "(l, " (marched-args desc) ");")]
                                           (if (= k (length marched)) [call]
                                               [(.. "if (kind == " k ") {") (.. "    " call) "}"])))})
                         [])
            :member-distance (if marched?
                                 ["return b.x < 0.0 ? fieldMarchedDistance(q, a, int(-b.x), int(b.w))"
                                  "                  : sdFieldShape(q, a, b.xyz);"]
                                 ["return sdFieldShape(q, a, b.xyz);"])
            :entry (if (not marched?) [(.. "t = min(t, " closed ");")]
                       closed [(.. "vec4 b = " record-b ";")
                               (.. "t = min(t, b.x < 0.0 ? " march)
                               (.. "                      : " closed ");")]
                       [(.. "vec4 b = " record-b ";")
                        (.. "t = min(t, " march ");")])})]))

(fn shader-functions [_ o _ defined]
  ;; Its spheres and boxes are round boxes (shaders/pipeline/field.glsl); its marched
  ;; members call their primitives: each definition not yet `defined`.
  (let [out []]
    (each [_ desc (ipairs o.field.descs)]
      (when (not (. defined desc.glsl-name))
        (tset defined desc.glsl-name true)
        (table.insert out (glsl.text-lines desc.glsl))))
    out))

(fn shader-gradients [_ _ _ defined]
  ;; fieldNormal takes the box's gradient.
  (when (not (. defined "gradBox"))
    (tset defined "gradBox" true)
    (glsl.text-lines (. (primitives.lookup :box) :gradient-glsl))))

(fn field-uniforms [plan o cam-pos]
  ;; Its grid, the low corner camera-relative (in double), and its textures (:type
  ;; :texture, {:width :height :data}; the same tables every frame, so a backend
  ;; uploads them once). A field of spheres walks one more texture (:walk?).
  (let [fd plan.field
        tex (field.textures fd)
        [x y z] fd.lo
        [cx cy cz] cam-pos]
    (local out [{:name "uFieldOrigin" :type :vec3 :values [(- x cx) (- y cy) (- z cz)]}
                {:name "uFieldSize" :type :vec3 :values fd.size}
                {:name "uFieldCell" :type :vec3 :values fd.cell}
                {:name "uFieldDims" :type :vec3 :values fd.dims}
                {:name "uFieldReach" :type :float :values [fd.reach]}
                {:name "uFieldCrossings" :type :int :values [fd.crossings]}
                ;; fieldRead's reciprocal row counts (texture widths are field.texture-width).
                {:name "uFieldRows" :type :vec4
                 :values (icollect [_ k (ipairs [:cells :records :objects :walk])]
                           (let [t (. tex k)] (if t (/ 1 t.height) 0)))}
                {:name "uFieldCells" :type :texture :texture tex.cells}
                {:name "uFieldRecords" :type :texture :texture tex.records}
                {:name "uFieldObjects" :type :texture :texture tex.objects}])
    (when o.count-read?
      (table.insert out {:name "uFieldCount" :type :int :values [fd.count]}))
    (when fd.walk?
      (table.insert out {:name "uFieldTurns" :type :int :values [fd.turns]})
      (table.insert out {:name "uFieldWalk" :type :texture :texture tex.walk}))
    out))

(local black [0 0 0])

(fn field-min [r d x y z skip]
  ;; The field's nearest listed member (fieldMap), skipping tape number `skip`.
  (let [own (and skip (+ 1 (- skip r.first)))
        df (field.distance r.field x y z own)]
    (if (< df d) df d)))

(fn field-color [run x y z d best r g b mirror rough emit]
  ;; Its nearest listed member (black, and no object, outside its grid), as fieldMap
  ;; and fieldColor; the mirror amount and material stay.
  (let [(df fb) (field.distance run.field x y z)]
    (if (< df d)
        (let [[cr cg cb] (if fb (. run.field.colors fb) black)
              hit (and fb (+ run.first fb -1))]
          (values df hit cr cg cb mirror rough emit))
        (values d best r g b mirror rough emit))))

{:name :field
 :doc "many flat spheres and boxes, from a grid in textures that a ray walks"
 :count (fn [o] o.field.count)
 :folds? false
 :marched? (fn [_] false)
 :infos (fn [_] nil)
 :describe (fn [o] (.. " of " o.field.count " objects (a grid in textures)"))
 :glsl {:distance (fn [_ _] (field-minimum "-1"))
        ;; (Its members are matte: the mirror amount and material stay.)
        :color (fn [_ o ?first] (color-lines o ?first))
        ;; Every member but `skip`, or member `only` alone; with `materials`,
        ;; mapColor's term.
        :object (fn [_ o first]
                  (glsl.either-terms
                   (color-lines o first)
                   ["if (all) {" (glsl.indented (field-minimum (field-index (+ first o.id) "skip"))) "}"
                    (field-selected o first "d = fieldObject" "only")]))
        :gradient (fn [_ o first action]
                    (when (exact? o) (field-selected o first (.. action "fieldNormal"))))
        :planes (fn [_ _] nil)
        : exact?}
 :lua (fn [tape o what _ into] (evaluators tape o what into))
 :spheres (fn [_ o at _] (+ at o.field.count))
 :run (fn [plan _ run] (doto run (tset :field plan.field)))
 :uniforms field-uniforms
 :shader {:functions shader-functions :gradients shader-gradients
          :sections (fn [plan _ fill] (field-lines plan fill))}
 :reference {:min field-min :color field-color :near runs.each-near}}
