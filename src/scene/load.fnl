;; Scene files: sandboxed evaluation, validation with file:line:field messages, and
;; defaults. A scene file is Fennel data; the result is plain data with every field set.

(local fennel (require :fennel))
(local features (require :src.render.features))
(local primitives (require :src.sdf.primitives))
(local operations (require :src.sdf.operations))
(local lower (require :src.sdf.lower))
(local custom (require :src.sdf.custom))
(local sandbox (require :src.scene.sandbox))
(local data (require :src.scene.data))
(local params (require :src.scene.params))
(local files (require :src.util.files))
(local text (require :src.util.text))

;; Globals that checking each object calls, read once: a module loaded with an :env
;; (the tests, tools/fnl.lua) reaches every global through a function, which was half
;; the time of validating 100,000 spheres.
(local type type)
;; `pairs` under another name: a loop over `pairs` by that name is LuaJIT's ITERN,
;; which Debian 12's LuaJIT ends early once despecialised (see src/util/wire.fnl).
(local each-pair pairs)
(local ipairs ipairs)
(local huge math.huge)
(local floor math.floor)

(local default-environment [0.901 0.976 1])

(fn fresh [default]
  "A default value for one scene: tables are copied, so that changing one loaded
scene never changes another's defaults."
  (if (= (type default) :table) (icollect [_ v (ipairs default)] v) default))

;; Each top-level section: field name -> {:type :default}. Types are checked by `check`.
(local sections
  {:camera {:pos {:type :vec3 :default [0 -10 2]}
            :yaw {:type :number :default 90}
            :pitch {:type :pitch :default 0}
            :fov {:type :fov :default 60}}
   :light {:pos {:type :vec3 :default [-30 20 20]}}
   ;; Defaults chosen from the accuracy report (report/report.md): a hit test relative
   ;; to the distance travelled, tetrahedron normals and over-relaxation 1.5 give the
   ;; seed scene a lower error than the article's settings (fixed 1e-4, one-sided
   ;; normals) at 1.6-1.9x the speed, at 320x180 and at 640x360. The article's 500
   ;; steps stay: cutting them flips grazing rays at the horizon for little time.
   :render {:max-steps {:type :steps :default 500}
            :epsilon {:type :non-negative :default 1e-4}
            :draw-distance {:type :positive :default 1000}
            :reflections {:type :reflections :default 3}
            :shadows {:type :boolean :default true}
            :glow {:type :boolean :default false}
            :scale {:type :scale :default 1}
            ;; Supersampling: N x N rays per pixel on a regular grid, averaged.
            :samples {:type :samples :default 1}
            ;; With :samples N > 1: the N x N rays only in pixels whose centre ray
            ;; finds an edge (shaders/pipeline/adaptive.glsl); the others take one.
            :adaptive {:type :boolean :default false}
            :hit-test {:type :hit-test :default :relative}
            :normals {:type :normal-method :default :tetrahedron}
            ;; Whose distance the normal differentiates: the nearest object's alone
            ;; (:object), or the whole scene's (:scene, the article's: across the
            ;; crease where two objects meet it points between them, and a mirror
            ;; bounce there lights a single pixel).
            :normals-of {:type :normals-of :default :object}
            :relaxation {:type :relaxation :default 1.5}
            ;; Bounding spheres tested before marching, ground planes in closed form
            ;; (src/render/bounds.fnl): the same image, several times faster.
            :bounds {:type :boolean :default true}
            ;; A ray that spends every step without a hit: :surface shades it where it
            ;; stopped (the article's: a dark smear along grazing silhouettes and the
            ;; horizon); :background lets it pass the finite objects to a ground plane
            ;; or the sky.
            :out-of-steps {:type :out-of-steps :default :background}}})

;; The modern lighting model (soft shadows, sky light, features), chosen by a :lighting
;; section; a scene without one keeps the article's classic model. Colours are sRGB as
;; picked; the shader works in linear light. Each feature is compiled in only when it
;; is on (see plan.fnl).
(local lighting-spec
  {:model {:type :model :default :modern}
   :sky-zenith {:type :color :default [0.3 0.5 0.85]}
   :sky-horizon {:type :color :default [0.75 0.85 0.95]}
   :sun-size {:type :sun-size :default 1.5}     ; the sun disc's radius, degrees (0: none)
   :ambient {:type :intensity :default 0.5}      ; light from the sky, times its colour
   :exposure {:type :intensity :default 1}})

;; And the features' own settings (src/render/features/: ambient occlusion, fog, rim
;; light, specular highlights).
(each [k v (each-pair (features.settings))] (tset lighting-spec k v))

(local light-specs
  {:sun {:direction {:type :direction :default [0.4 -0.3 0.85]}   ; toward the sun
         :color {:type :color :default [1 0.95 0.85]}
         :intensity {:type :intensity :default 3}
         :softness {:type :softness :default 0.05}}
   :point {:pos {:type :vec3 :default [0 0 10]}
           :color {:type :color :default [1 1 1]}
           :intensity {:type :intensity :default 3}
           :range {:type :positive :default 10}   ; half the light is left at this distance
           :softness {:type :softness :default 0}}})

(local light-kinds [:point :sun])
(local max-lights 8)

(local hit-tests [:fixed :relative :pixel])
(local normal-methods [:one-sided :central :tetrahedron])

(local top-level-keys [:name :camera :light :environment :render :lighting :objects])

(local limits {:max-reflections 16 :max-steps 100000
               ;; Flat objects (sphere, box, plane): 1,000,000 made by a loop load in
               ;; 2.4 s here in this process (sandbox 1.9 s, validation), 100,000
               ;; in 0.24 s. Objects with a tree count against :max-nodes as well.
               :max-objects 1000000
               ;; Coordinates and lengths: float32 holds them with room to spare
               ;; (positions are sent camera-relative), and the image stays meaningful.
               :world 1e7 :min-length 1e-6 :max-epsilon 10 :min-fov 0.1 :max-fov 179
               :max-name 80
               ;; Scene trees: depth and size. The shader's size is the plan's to
               ;; check (src/render/plan.fnl's max-written-nodes: objects of one
               ;; structure share one loop); here the nodes of all objects together,
               ;; as many as the objects allowed, each validated in turn.
               :max-depth 32 :max-nodes 1000000})

;;; Messages

(fn suggestion [word candidates]
  "A ' (did you mean :x?)' hint when a candidate is close to `word`, else ''.
Long words get none: no name is that long, and the distance would cost time."
  (var best nil)
  (var best-distance math.huge)
  (each [_ c (ipairs candidates) &until (> (length word) text.max-shown)]
    (let [d (text.edit-distance word c)]
      (when (< d best-distance)
        (set best c)
        (set best-distance d))))
  (if (and best (<= best-distance (math.max 1 (math.floor (/ (length word) 3)))))
      (.. " (did you mean :" best "?)")
      ""))

(fn describe-value [v]
  (if (= (type v) :number)
      (if (not= v v) "nan"
          (= v math.huge) "inf"
          (= v (- math.huge)) "-inf"
          (tostring v))
      (= (type v) :string) (if (> (length v) text.max-shown)
                               (.. "a string of " (length v) " bytes")
                               (text.quote-string v))
      (= (type v) :function) "a function"
      (= (type v) :table) (let [n (length v)]
                            (if (and (> n 0) (= (next v n) nil)) (.. "a list of " n " items")
                                (= (next v) nil) "an empty table"
                                "a table"))
      (tostring v)))

(fn path->string [path]
  (var out "")
  (each [_ p (ipairs path)]
    (set out (if (= (type p) :number)
                 (.. out "[" p "]")
                 (not (text.name? p)) (.. out "[" (text.quote-string p) "]")
                 (= out "") p
                 (.. out "." p))))
  out)

;;; Source lines for fields, from the parsed form of the file

(fn node-line [node]
  (let [src (fennel.ast-source node)]
    (and src src.line)))

(fn key-line [source node key]
  "Line of `:key` inside the table literal `node`, found in the source text."
  (let [src (fennel.ast-source node)]
    (when (and src src.bytestart src.byteend (= (type key) :string))
      (let [text (source:sub src.bytestart src.byteend)
            at (text:find (.. ":" (key:gsub "%p" "%%%0") "[%s%)%]}]") 1)]
        (when at
          (let [(_ newlines) (: (text:sub 1 at) :gsub "\n" "")]
            (+ src.line newlines)))))))

(fn ast-of [ctx path]
  ;; The parsed last form; a plain data file's is read again with source fields when
  ;; a message needs a line (the load itself does without them), only the tables
  ;; along `path` built.
  (if (and (= nil ctx.ast) ctx.ast-fn) (ctx.ast-fn path) ctx.ast))

(fn line-for [ctx path]
  "Best known line for `path`: the line of the deepest literal that matches it."
  (var node (ast-of ctx path))
  (var line (and node (= (type node) :table) (node-line node)))
  (var done? (not= (type node) :table))
  (each [_ key (ipairs path) &until done?]
    (let [child (. node key)
          kline (key-line ctx.source node key)]
      (when kline (set line kline))
      (if (and (= (type child) :table) (not (fennel.list? child)) (not (fennel.sym? child)))
          (do (set node child)
              (let [l (node-line child)] (when (and l (not kline)) (set line l))))
          (do (when (and (= (type child) :table) (not kline))
                ;; A symbol or a call in place of a value: its own line.
                (let [l (node-line child)] (when l (set line l))))
              (set done? true)))))
  line)

(fn sub-path [path key]
  (doto (icollect [_ p (ipairs path)] p) (table.insert key)))

(fn short-path [s]
  ;; A deep tree's path would fill the message: keep its two ends.
  (if (> (length s) 120) (.. (s:sub 1 50) " ... " (s:sub -60)) s))

(fn fail [ctx path reason ?line]
  (let [line (or ?line (line-for ctx path))
        where (if line (.. ctx.file ":" line) ctx.file)
        field (short-path (path->string path))]
    (error {:scene-error (if (= field "")
                             (.. where ": " reason)
                             (.. where ": " field ": " reason))})))

;;; Field checks: each returns the cleaned value or calls `fail`

(fn finite? [v]
  (and (= (type v) :number) (= v v) (not= v huge) (not= v (- huge))))

(fn check-number [ctx path v what ok?]
  (when (not (finite? v))
    (fail ctx path (.. "must be " what ", got " (describe-value v))))
  (when (and ok? (not (ok? v)))
    (fail ctx path (.. "must be " what ", got " (describe-value v))))
  v)

(fn check-integer [ctx path v lo hi]
  (check-number ctx path v (.. "an integer from " lo " to " hi)
                #(and (= $ (math.floor $)) (<= lo $ hi))))

(fn check-vec3 [ctx path v what element-what element-ok?]
  (when (or (not= (type v) :table) (not= (length v) 3))
    (fail ctx path (.. "must be " what ", got " (describe-value v))))
  (each [k _ (each-pair v)]
    (when (or (not= (type k) :number) (not= k (floor k)) (< k 1) (> k 3))
      (fail ctx path (.. "must be " what " with exactly three numbers"))))
  ;; Not ipairs: [nil nil 5] has length 3 and no first element.
  (fcollect [i 1 3]
    (check-number ctx (sub-path path i) (. v i) element-what element-ok?)))

(fn coordinate? [v] (<= (- limits.world) v limits.world))
(fn length? [v] (<= limits.min-length v limits.world))

;; The number and vector types: what a value must be, as the message says it, and
;; the test each number must pass besides being finite. `check` and `quick-check`
;; (the fast path for plain values) both read them.
(local number-types
  {:number {:what "a number from -1e7 to 1e7" :ok? coordinate?}
   :positive {:what "a positive number from 1e-6 to 1e7" :ok? length?}
   :non-negative {:what "a number from 0 to 10" :ok? #(<= 0 $ limits.max-epsilon)}
   :pitch {:what "a number of degrees from -90 to 90" :ok? #(<= -90 $ 90)}
   :fov {:what "a number of degrees from 0.1 to 179"
         :ok? #(<= limits.min-fov $ limits.max-fov)}
   :scale {:what "a render scale above 0 and at most 1" :ok? #(and (> $ 0) (<= $ 1))}
   :relaxation {:what "an over-relaxation factor from 1 up to (not including) 2"
                :ok? #(and (>= $ 1) (< $ 2))}
   :fraction {:what "a number from 0 to 1" :ok? #(<= 0 $ 1)}
   :intensity {:what "a number from 0 to 1000" :ok? #(<= 0 $ 1000)}
   :emission {:what "a number from 0 to 100" :ok? #(<= 0 $ 100)}
   :softness {:what "a penumbra width per unit distance from 0 to 1" :ok? #(<= 0 $ 1)}
   :sun-size {:what "a number of degrees from 0 to 20" :ok? #(<= 0 $ 20)}
   :fog {:what "a number from 0 to 10" :ok? #(<= 0 $ 10)}
   :length0 {:what "a number from 0 to 1e7" :ok? #(<= 0 $ limits.world)}})

(local vec3-types
  {:vec3 {:what "a list of three numbers like [1 2 3]"
          :element "a number from -1e7 to 1e7" :ok? coordinate?}
   :size3 {:what "three positive numbers like [1 1 1]"
           :element "a positive number from 1e-6 to 1e7" :ok? length?}
   :color {:what "a colour of three numbers from 0 to 1"
           :element "a colour of three numbers from 0 to 1" :ok? #(<= 0 $ 1)}
   :lengths3 {:what "three numbers from 0 to 1e7 like [2 2 0]"
              :element "a number from 0 to 1e7" :ok? #(<= 0 $ limits.world)}
   :counts3 {:what "three whole numbers from 0 to 1000 like [3 3 0]"
             :element "a whole number from 0 to 1000"
             :ok? #(and (= $ (math.floor $)) (<= 0 $ 1000))}})

(fn quick-check [v kind]
  "`v` as `check` returns it when it is a plain valid value of a number or vector
type, found without building a path or a message; else nil, and `check` gives the
verdict. Large scenes are mostly such values."
  (let [n (. number-types kind)
        t (. vec3-types kind)]
    (if n (when (and (finite? v) (n.ok? v)) v)
        (and t (= (type v) :table))
        (let [x (. v 1) y (. v 2) z (. v 3)
              ok? t.ok?]
          ;; Three finite numbers at 1, 2 and 3 and nothing else: the only keys.
          (when (and (finite? x) (finite? y) (finite? z) (ok? x) (ok? y) (ok? z)
                     (= 3 (accumulate [keys 0 _ (each-pair v)] (+ keys 1))))
            [x y z])))))

(fn check-choice [ctx path v choices]
  (var found? false)
  (each [_ c (ipairs choices)] (when (= c v) (set found? true)))
  (if found? v
      (fail ctx path (.. "must be one of :" (table.concat choices " :") ", got "
                         (if (= (type v) :string)
                             (.. (text.keyword v) (suggestion v choices))
                             (describe-value v))))))

(fn check-name [ctx v]
  (if (not= (type v) :string)
      (fail ctx [:name] (.. "must be a string, got " (describe-value v)))
      (or (> (length v) limits.max-name) (not (text.valid-utf8? v)) (v:find "[%c]"))
      (fail ctx [:name] (.. "must be a line of UTF-8 text of at most " limits.max-name
                            " bytes, got " (if (> (length v) limits.max-name)
                                               (.. "a string of " (length v) " bytes")
                                               (text.quote-string v))))
      v))

;;; Functions of time: a value given as (fn [t] ...) is evaluated at t = 0 here, and
;;; again every frame by `animate`, each call with its own small step budget.

;; Types whose values only reach uniforms; the others change the shader.
(local animatable {:number true :positive true :vec3 true :size3 true :color true
                   :direction true :degrees true :fraction true :length0 true :lengths3 true
                   :pitch true :fov true :intensity true :emission true :softness true :sun-size true
   :fog true})

;; Lua steps one call of a function of time may take (it runs every frame).
(local time-steps 100000)
;; And all of them together, per frame (the player's, a recorded one, the first at
;; t = 0 when the file loads): 1 million steps, about 11 ms here (measured: 30
;; functions of 90,000 steps each, stopped at the millionth step). 8000
;; functions just under their own limit took 12 s a frame (and 14 s to load) before.
(local frame-steps 1000000)

(fn time-text [t]
  "A time `t` (seconds) for a message, to the millisecond: 0.332, not 0.332117609."
  (tostring (/ (math.floor (+ (* t 1000) 0.5)) 1000)))

(fn time-call [ctx path f t]
  ;; ctx.time-budget: the steps the functions of time have left for this frame.
  (let [budget ctx.time-budget
        allowed (if budget (math.max 1 (math.min time-steps budget.left)) time-steps)
        (ok? v used) (sandbox.run (fn [] (f t)) ctx.file ctx.env {:steps allowed :collect? false})]
    (when budget (set budget.left (- budget.left used)))
    (if ok? v
        (and budget (< allowed time-steps) (>= used allowed) (sandbox.sandbox-error? v))
        (fail ctx path (.. "the functions of time took more than " (/ frame-steps 1000000)
                           " million steps together for one frame (at t = " (time-text t)
                           "): fewer of them, or cheaper ones"))
        (fail ctx path (.. "the function of time failed at t = " (time-text t) ": "
                           (sandbox.error-message v))))))

(fn check-animated [ctx path f kind checker]
  (when (not (. animatable kind))
    (fail ctx path "cannot be a function of time: it changes the shader, not only its values"))
  (let [v (time-call ctx path f 0)]
    (when (= (type v) :function)
      (fail ctx path "a function of time must return a value, not another function"))
    ;; The checker takes the time too (for its message; a check of a worker's value
    ;; gives none).
    (let [checked (checker v 0)]
      (table.insert ctx.animated {: path : f : checker :checker-ctx ctx})
      checked)))

(var check nil)

(set check (fn [ctx path v kind]
  (if (= (type v) :function)
      (check-animated ctx path v kind #(check ctx path $ kind))
      (. number-types kind)
      (let [n (. number-types kind)] (check-number ctx path v n.what n.ok?))
      (. vec3-types kind)
      (let [t (. vec3-types kind)] (check-vec3 ctx path v t.what t.element t.ok?))
      (case kind
    :steps (check-integer ctx path v 1 limits.max-steps)
    :reflections (check-integer ctx path v 0 limits.max-reflections)
    :hit-test (check-choice ctx path v hit-tests)
    :normal-method (check-choice ctx path v normal-methods)
    :boolean (if (= (type v) :boolean) v
                 (fail ctx path (.. "must be true or false, got " (describe-value v))))
    :direction (let [v (check-vec3 ctx path v "a direction of three numbers like [0 0 1]"
                                   "a number from -1e7 to 1e7" coordinate?)
                     [x y z] v
                     len (math.sqrt (+ (* x x) (* y y) (* z z)))]
                 (if (< len limits.min-length)
                     (fail ctx path (.. "must be a direction, not all zero, got ["
                                        (table.concat (icollect [_ c (ipairs v)] (describe-value c)) " ")
                                        "]"))
                     [(/ x len) (/ y len) (/ z len)]))
    :model (check-choice ctx path v [:classic :modern])
    :out-of-steps (check-choice ctx path v [:background :surface])
    :normals-of (check-choice ctx path v [:object :scene])
    :samples (check-integer ctx path v 1 4)
    _ (error (.. "unknown field type " (tostring kind)))))))

(fn check-param [ctx path v spec]
  "Check one descriptor parameter (see src/sdf/primitives.fnl for the types)."
  (case (if (= (type v) :function) :function spec.type)
    :function (check-animated ctx path v spec.type #(check-param ctx path $ spec))
    :degrees (check-number ctx path v (.. "a number of degrees from " spec.min " to " spec.max)
                           #(<= spec.min $ spec.max))
    :count (check-number ctx path v (.. "a whole number from " (or spec.min 1) " to " (or spec.max 64))
                         #(and (= $ (math.floor $)) (<= (or spec.min 1) $ (or spec.max 64))))
    :choice (check-choice ctx path v spec.choices)
    other (check ctx path v other)))

(fn key-before? [a b]
  "The order in which a message picks the first bad key: entries that are not names
(numbers ascending), then names alphabetically. pairs order changes from run to run;
a message must not."
  (let [ta (type a) tb (type b)]
    (if (not= ta tb) (if (= ta :string) false (= tb :string) true (< ta tb))
        (or (= ta :string) (= ta :number)) (< a b)
        (< (describe-value a) (describe-value b)))))

(fn check-keys [ctx path tbl allowed]
  (let [bad (icollect [k _ (each-pair tbl)]
              (when (or (not= (type k) :string)
                        (not (accumulate [known? false _ a (ipairs allowed) &until known?]
                               (= a k))))
                k))]
    (when (> (length bad) 0)
      (let [k (. (doto bad (table.sort key-before?)) 1)]
        (if (not= (type k) :string)
            (fail ctx path (.. "unexpected entry " (describe-value k) "; fields are named, like :"
                               (. allowed 1)))
            (let [sorted (doto (icollect [_ a (ipairs allowed)] a) table.sort)]
              (fail ctx (sub-path path k)
                    (.. "unknown field" (suggestion k allowed)
                        "; known fields: :" (table.concat sorted " :")))))))))

(fn check-fields [ctx path given spec]
  (let [fields (doto (icollect [k (each-pair spec)] k) table.sort)
        given (or given {})
        out {}]
    (when (or (not= (type given) :table) (not= nil (. given 1)))
      (fail ctx path (.. "must be a table like {:" (. fields 1) " ...}, got " (describe-value given))))
    (check-keys ctx path given fields)
    (each [_ field (ipairs fields)]
      (let [v (. given field)
            f (. spec field)]
        (tset out field (if (= v nil) (fresh f.default) (check ctx (sub-path path field) v f.type)))))
    out))

(fn check-section [ctx name value]
  (check-fields ctx [name] value (. sections name)))

(fn check-light [ctx path l]
  (when (or (not= (type l) :table) (not= nil (. l 1)))
    (fail ctx path (.. "must be a light like {:kind :sun :direction [0 -1 2]}, got "
                       (describe-value l))))
  (when (= l.kind nil)
    (fail ctx path "missing :kind (:sun, a light from a direction, or :point)"))
  (let [kind (check-choice ctx (sub-path path :kind) l.kind light-kinds)
        rest (collect [k v (each-pair l)] (when (not= k :kind) (values k v)))]
    (doto (check-fields ctx path rest (. light-specs kind))
      (tset :kind kind))))

(fn check-lighting [ctx value light]
  "The :lighting section, or nil for the classic model. Without :lights, one sun
shines from where the classic :light is (seen from the origin)."
  (when (not= value nil)
    (when (or (not= (type value) :table) (not= nil (. value 1)))
      (fail ctx [:lighting] (.. "must be a table like {:model :modern}, got " (describe-value value))))
    (let [lights value.lights
          rest (collect [k v (each-pair value)] (when (not= k :lights) (values k v)))
          out (check-fields ctx [:lighting] rest lighting-spec)
          path [:lighting :lights]]
      (set out.lights
           (if (= lights nil)
               (let [[x y z] light.pos
                     len (math.sqrt (+ (* x x) (* y y) (* z z)))]
                 ;; A sun with the defaults of light-specs, but its direction.
                 [(doto (collect [field f (each-pair light-specs.sun)] field (fresh f.default))
                    (tset :kind :sun)
                    (tset :direction (if (> len 0) [(/ x len) (/ y len) (/ z len)] [0 0 1])))])
               (do
                 (when (or (not= (type lights) :table)
                           (accumulate [bad? false k (each-pair lights)]
                             (or bad? (not= (type k) :number) (< k 1) (> k (length lights)))))
                   (fail ctx path (.. "must be a list of lights like [{:kind :sun}], got "
                                      (describe-value lights))))
                 (when (> (length lights) max-lights)
                   (fail ctx path (.. "has " (length lights) " lights; at most " max-lights
                                      " are allowed (remove " (- (length lights) max-lights) ")")))
                 (icollect [i l (ipairs lights)] (check-light ctx (sub-path path i) l)))))
      (when (= out.model :modern) out))))

(fn all-kind-names []
  (let [names (primitives.kind-names)]
    (each [_ k (ipairs (operations.kind-names))] (table.insert names k))
    (table.insert names :custom)
    (doto names table.sort)))

;; Fields every tree node may carry: placement shorthands and its material.
(local shorthand-fields [:pos :rotate :scale :color :mirror :roughness :emission])
(local shorthand-types {:pos :vec3 :rotate :vec3 :scale :positive :color :color :mirror :fraction
                        :roughness :fraction :emission :emission})
;; Material fields that only the modern model reads.
(local modern-fields {:roughness true :emission true})

;; The article's three kinds, written as it does (only these fields), are checked
;; by a quicker path (a scene of 100,000 spheres): they are the same leaves as tree
;; nodes (see src/sdf/lower.fnl's node-of), drawn alike.
(local grouped-fields {:sphere {:kind true :pos true :radius true :color true}
                       :box {:kind true :pos true :size true :color true}
                       :plane {:kind true :height true :color true}})

;; Their fields in order, with types and defaults: the placement, the primitive's own
;; parameters, the colour.
(local grouped-params
  (collect [kind fields (each-pair grouped-fields)]
    (let [desc (primitives.lookup kind)
          out []]
      (when fields.pos (table.insert out {:name :pos :type :vec3 :default [0 0 0]}))
      (each [_ p (ipairs desc.params)]
        (when (. fields p.name) (table.insert out p)))
      (table.insert out {:name :color :type :color :default [1 1 1]})
      (values kind out))))

(fn grouped? [o]
  (let [allowed (. grouped-fields o.kind)]
    (and allowed (accumulate [ok? true k (each-pair o)] (and ok? (= true (. allowed k)))))))

(fn check-grouped [ctx i o]
  (let [out {:kind o.kind :index i}]
    (each [_ p (ipairs (. grouped-params o.kind))]
      (let [v (. o p.name)]
        ;; A path only for the values the quick check does not pass.
        (tset out p.name (if (= v nil) (fresh p.default)
                             (or (quick-check v p.type)
                                 (check ctx [:objects i p.name] v p.type))))))
    out))

;; A custom node's fields beside :distance and :params (src/sdf/custom.fnl).
(local custom-spec
  {:params [{:name :bounds :type :size3 :required? true
             :missing "missing; a custom node needs :bounds [hx hy hz], the half extents of a box about its origin that holds the shape"}
            {:name :lipschitz :type :positive :optional? true}
            {:name :trust-lipschitz :type :boolean :optional? true}]
   :extra-fields [:distance :params :ranges]})

(fn bounds-message [low on on-face? bounds ?box ?spent?]
  ;; Why a custom node's :bounds are refused: its distance `low` at `on`, on a face
  ;; of the box or outside it.
  (let [g #(string.format "%.3g" $)
        box-text #(.. "[" (table.concat (icollect [_ v (ipairs $)] (g v)) " ") "]")]
    (.. "the distance is " (g low) " at (" (table.concat (icollect [_ v (ipairs on)] (g v)) ", ")
        (if on-face? ") on the box's face, so the shape crosses its bounds "
            ") outside the box, so the shape lies beyond its bounds ")
        (box-text bounds)
        (if ?box (.. "; a box that holds it: " (box-text ?box))
            ?spent? "; the search for a box that holds it stopped at its budget (a costly function): grow :bounds until the loader takes them"
            (.. "; no box up to " custom.limits.bounds-growth
                " times as large holds it (is the distance negative far from the shape?)")))))

;;; Custom parameters that take a range of values. A function of time's range is
;;; declared in :ranges; a slider's (param :r 1 {:min 0.5 :max 2}) written as the value
;;; (or as a name bound to one) is its :min and :max. The factor and the bounds are
;;; checked over the range, so no value the node takes was left out.

(fn range-text [[lo hi]]
  (.. "[" (describe-value lo) " " (describe-value hi) "]"))

(fn check-ranges [ctx path given names]
  "The custom node's :ranges `given` ({name [lo hi]}, names among `names`, its
:params' names as a set), cleaned: {} when there are none."
  (let [rpath (sub-path path :ranges)]
    (if (= nil given) {}
        (do (when (or (not= (type given) :table) (not= nil (. given 1)))
              (fail ctx rpath (.. "must be a table of the values parameters take, like {:r [0.5 2]}, got "
                                  (describe-value given))))
            (collect [_ k (ipairs (doto (icollect [k (each-pair given)] k) (table.sort key-before?)))]
              (let [kpath (sub-path rpath k)
                    r (. given k)]
                (when (or (not= (type k) :string) (not (. names k)))
                  (fail ctx (if (= (type k) :string) kpath rpath)
                        (.. (if (= (type k) :string) "is" (.. "has " (describe-value k) ", which is"))
                            " not a parameter in the node's :params; :ranges names parameters, like {:r [0.5 2]}")))
                (when (not (and (= (type r) :table) (= 2 (accumulate [c 0 _ (each-pair r)] (+ c 1)))
                                (finite? (. r 1)) (finite? (. r 2))
                                (coordinate? (. r 1)) (coordinate? (. r 2)) (<= (. r 1) (. r 2))))
                  (fail ctx kpath (.. "must be two numbers [lo hi] from -1e7 to 1e7, lo at most hi, like [0.5 2], got "
                                      (describe-value r))))
                (values k [(. r 1) (. r 2)])))))))

(fn in-range [ctx path v r ?function?]
  "`v` when it lies in range `r` of parameter `path`; else a failure (for a
function of time's value, at `?function?`, the time it was called at or true)."
  (let [[lo hi] r]
    (if (<= lo v hi) v
        (= ?function? nil)
        (fail ctx path (.. "is " (describe-value v) ", outside its declared range " (range-text r)))
        (fail ctx path (.. "the function of time gave " (describe-value v)
                           (if (= (type ?function?) :number) (.. " at t = " (time-text ?function?)) "")
                           ", outside its declared range " (range-text r))))))

(fn plain-table? [node]
  (and (= (type node) :table) (not (fennel.list? node)) (not (fennel.sym? node))))

(fn form-at [node path]
  ;; The form at `path` in the literal `node` (nil where a step is not a literal).
  (var node node)
  (each [_ key (ipairs path) &until (= node nil)]
    (set node (when (plain-table? node) (. node key))))
  node)

(fn index-forms [ctx]
  ;; Once per load: the scene's table literals by the form of their :distance, and
  ;; the forms bound to each name by local, var or let (for a slider given a name).
  (when (not ctx.form-index)
    (let [by-distance {}
          bindings {}]
      (fn bind! [name form]
        (when (fennel.sym? name)
          (let [k (tostring name)]
            (when (not (. bindings k)) (tset bindings k []))
            (table.insert (. bindings k) form))))
      (fn walk [node depth]
        (when (and (= (type node) :table) (not (fennel.sym? node)) (< depth 200))
          (when (and (plain-table? node) (fennel.list? (. node :distance)))
            (tset by-distance (. node :distance) node))
          (when (and (fennel.list? node) (fennel.sym? (. node 1)))
            (case (tostring (. node 1))
              (where (or "local" "var")) (bind! (. node 2) (. node 3))
              "let" (when (fennel.sequence? (. node 2))
                      (for [i 1 (length (. node 2)) 2]
                        (bind! (. node 2 i) (. node 2 (+ i 1)))))))
          (each [k v (each-pair node)]
            (walk k (+ depth 1))
            (walk v (+ depth 1)))))
      (walk ctx.forms 0)
      (set ctx.form-index {: by-distance : bindings})))
  ctx.form-index)

(fn param-call-name [form]
  (when (and (fennel.list? form) (fennel.sym? (. form 1)) (= (tostring (. form 1)) "param")
             (= (type (. form 2)) :string))
    (. form 2)))

(fn slider-range [ctx path o k v]
  "The range [min max] of the slider that gives custom node `o`'s parameter `k` its
value `v`: when the value is written as (param :name v {:min :max}), or as a name
bound (by local, var or let, only so) to one; else nil. Only in the process that
ran the scene (its sliders are known)."
  (when (and ctx.sliders (next ctx.sliders) ctx.forms)
    (let [index (index-forms ctx)
          form (or (form-at ctx.ast (sub-path (sub-path path :params) k))
                   (case (custom.find-form o.distance ctx.forms ctx.file)
                     fn-form (form-at (. index.by-distance fn-form) [:params k])))
          name (or (param-call-name form)
                   (when (fennel.sym? form)
                     (let [names (icollect [_ f (ipairs (or (. index.bindings (tostring form)) []))]
                                   (or (param-call-name f) false))
                           first (. names 1)]
                       (when (and first (accumulate [same? true _ n (ipairs names)] (and same? (= n first))))
                         first))))
          p (and name (. ctx.sliders name))]
      ;; The value the call gave: a name shadowed by another binding gives another.
      (when (and p (= p.kind :number) (= p.value v))
        [p.min p.max]))))

;; Measures and bounds checks of custom nodes, kept across loads: the scene worker
;; loads the whole scene again at every drag of a slider and every value edit, and
;; a node measured over its slider's range measures the same at every value. Keyed
;; by the function's Lua text, its bounds and the values it is checked at; a measure
;; other than custom.measure (a test's, the answer check's: ctx.measure) has a
;; cache of its own. At most `checks-kept` entries each, emptied when full.
(local checks-kept 64)
(local measure-caches (setmetatable {} {:__mode :k}))
(local bounds-cache {:n 0 :entries {}})

(fn remembered [ctx field cache key f]
  ;; What `f` gives, computed once per `key`: kept in this load's ctx[field] (a scene
  ;; of a thousand nodes from a loop shares them, however many) and in `cache`
  ;; ({:n :entries}, kept across loads).
  (when (not (. ctx field)) (tset ctx field {}))
  (let [here (. ctx field)]
    (when (not (. here key))
      (when (not (. cache.entries key))
        (when (>= cache.n checks-kept)
          (set cache.entries {})
          (set cache.n 0))
        (set cache.n (+ cache.n 1))
        (tset cache.entries key (f)))
      (tset here key (. cache.entries key)))
    (. here key)))

(fn limits-text []
  ;; The measure's and the bounds check's limits, in the key of what they found (a
  ;; test changes them).
  (table.concat (doto (icollect [k v (each-pair custom.limits)] (.. k "=" (tostring v))) table.sort) " "))

(fn values-text [at]
  ;; "r = 2 and s = 0.3" for a sample's ranged values `at`, or nil when none.
  (let [names (doto (icollect [n (each-pair at)] n) table.sort)]
    (when (> (length names) 0)
      (table.concat (icollect [_ n (ipairs names)] (.. n " = " (describe-value (. at n)))) " and "))))

(fn jump-message [jump ?values]
  ;; The refusal of a distance that jumps outside its shape (custom.measure's jump).
  (let [[x y z] jump.at]
    (string.format "jumps from %.3g to %.3g at [%.3g %.3g %.3g]%s, outside the shape: a ray steps past a surface by the jump, which no :lipschitz covers; make it continuous there (math.mix in place of an if), or add :lipschitz 1 :trust-lipschitz true"
                   jump.low jump.high x y z (case ?values text (.. " with " text) _ ""))))

(fn check-custom! [ctx path o out]
  "Translate custom node `o`'s distance function, check that its :bounds hold the
shape and measure its Lipschitz factor, into `out`: :custom (the texts), :params,
:lipschitz (the factor used: the declared one when :trust-lipschitz)."
  (let [dpath (sub-path path :distance)
        ppath (sub-path path :params)
        given (or o.params {})]
    (when (and out.trust-lipschitz (not out.lipschitz))
      (fail ctx (sub-path path :trust-lipschitz)
            "trusts a declared factor, but the node declares none: add :lipschitz k (the factor its distance is divided by), or leave :trust-lipschitz out"))
    (when (not= (type o.distance) :function)
      (fail ctx dpath (.. (if (= nil o.distance) "missing; a custom node needs " "must be ")
                          "a distance function like (fn [x y z] (- (math.sqrt (+ (* x x) (* y y) (* z z))) 1))"
                          (if (= nil o.distance) "" (.. ", got " (describe-value o.distance))))))
    (when (or (not= (type given) :table) (not= nil (. given 1)))
      (fail ctx ppath (.. "must be a table of named numbers like {:radius 1}, got " (describe-value given))))
    (let [names (doto (icollect [k (each-pair given)] k) (table.sort key-before?))]
      (each [_ k (ipairs names)]
        (when (not= (type k) :string)
          (fail ctx ppath (.. "unexpected entry " (describe-value k) "; parameters are named, like {:radius 1}"))))
      (set out.ranges (check-ranges ctx path o.ranges (collect [_ k (ipairs names)] k true)))
      (set out.params
           (collect [_ k (ipairs names)]
             (let [kpath (sub-path ppath k)
                   v (. given k)
                   r (. out.ranges k)]
               (values k (if (and (= (type v) :function) (not r))
                             (fail ctx kpath (.. "a function of time; declare the values it takes, like :ranges {:"
                                                 k " [0.5 2]}, so that the distance's factor holds for all of them"))
                             (and r (= (type v) :function))
                             (check-animated ctx kpath v :number
                                             #(in-range ctx kpath (check ctx kpath $1 :number) r (or $2 true)))
                             r (in-range ctx kpath (check ctx kpath v :number) r)
                             (check ctx kpath v :number)))))))
    (when (= nil (next out.ranges)) (set out.ranges nil))
    ;; ctx.capture and ctx.measure: the main process's check of a scene worker's answer
    ;; (src/scene/answer.fnl) gives the worker's texts and measure, checked, instead.
    (case ((or ctx.capture custom.capture) o.distance ctx.forms ctx.file)
      (nil msg line) (fail ctx dpath msg line)
      t (let [line (. (debug.getinfo o.distance :S) :linedefined)
              declared (collect [_ n (ipairs t.params)] n true)]
          (each [_ n (ipairs t.params)]
            (when (= nil (. out.params n))
              (fail ctx dpath (.. "its parameter `" n "` has no value: add it to :params, like :params {:"
                                  n " 1}") line)))
          (each [_ n (ipairs (doto (icollect [k (each-pair out.params)] k) table.sort))]
            (when (not (. declared n))
              (fail ctx (sub-path ppath n) (.. "is not a parameter of the distance function; name it after x y z: (fn [x y z "
                                               (table.concat t.params " ") (if (> (length t.params) 0) " " "") n "] ...)"))))
          ;; One GLSL function per distinct text, named in the order met.
          (set ctx.customs (or ctx.customs {:n 0}))
          (when (not (. ctx.customs t.glsl))
            (set ctx.customs.n (+ ctx.customs.n 1))
            (tset ctx.customs t.glsl ctx.customs.n))
          (let [index (. ctx.customs t.glsl)
                glsl (t.glsl:gsub "sdCustom" (.. "sdCustom" index))
                data {:glsl glsl :lua t.lua :glsl-name (.. "sdCustom" index) :key (custom.digest glsl)
                      :params t.params :cost t.cost}
                ;; The check of the texts (the app's, here too) refuses what the
                ;; translator should never write: said as such, not as a table.
                desc (case (pcall custom.descriptor {:kind :custom :custom data})
                       (true d) d
                       (_ e) (fail ctx dpath
                                   (.. "its translation was refused by the check of the translator's texts ("
                                       (if (and (= (type e) :table) e.reason) e.reason (tostring e))
                                       "): a bug in the translator; please report it with this file")
                                   line))
                ;; The ranges: declared, else a slider's where one gives the value.
                ranges (collect [_ n (ipairs t.params)]
                         (values n (or (?. out.ranges n) (slider-range ctx path o n (. out.params n)))))
                samples (custom.range-samples t.params out.params ranges)
                cost (custom.sample-cost t.cost (length samples))
                measure (or ctx.measure custom.measure)
                key (.. (limits-text) "\n" t.lua "\n" (table.concat (icollect [_ v (ipairs out.bounds)] (string.format "%.17g" v)) " ")
                        (table.concat (icollect [_ s (ipairs samples)]
                                        (.. "\n" (table.concat (icollect [_ v (ipairs s.args)] (string.format "%.17g" v)) " ")))))
                mcache (or (. measure-caches measure)
                           (let [c {:n 0 :entries {}}] (tset measure-caches measure c) c))]
            (each [_ s (ipairs samples)] (table.insert s.args 1))
            ;; Each sample's measure, the largest taken: the factor holds for every
            ;; value the node's parameters take. The first that is not a number stops.
            (var (measured at) (values nil nil))
            (each [_ r (ipairs (remembered ctx :measures mcache key
                                           #(accumulate [done [] _ s (ipairs samples)
                                                         &until (and (. done 1) (= nil (. done (length done) :m)))]
                                              (let [(m where point jump) (measure desc.cpu out.bounds s.args cost)]
                                                (doto done (table.insert {: m : where : point : jump :at s.at}))))))]
              (if (= r.m nil)
                  (fail ctx dpath (string.format "%s at [%.3g %.3g %.3g]%s (sampled over its bounds grown by half: it must give a number everywhere there)"
                                                 r.where (. r.point 1) (. r.point 2) (. r.point 3)
                                                 (case (values-text r.at) text (.. ", with " text) _ ""))
                        line)
                  (when (or (= measured nil) (> r.m measured)) (set (measured at) (values r.m r.where))))
              (when (and r.jump (not out.trust-lipschitz))
                (fail ctx dpath (jump-message r.jump (values-text r.at)) line)))
            ;; The shape within its bounds (the distance is a number there: measured)
            ;; at each sample; a box that holds it at all of those that cross.
            (let [crossings (remembered ctx :bounds-checks bounds-cache key
                                        #(icollect [_ s (ipairs samples)]
                                           (case [(custom.check-bounds desc.cpu out.bounds s.args cost)]
                                             [low on on-face? ?box ?spent?] {: low : on : on-face? :box ?box :spent? ?spent? :at s.at})))]
              ;; Said at the lowest value found.
              (table.sort crossings #(< $1.low $2.low))
              (case (. crossings 1)
                first (let [boxes (icollect [_ c (ipairs crossings)] c.box)
                            box (when (= (length boxes) (length crossings))
                                  (fcollect [a 1 3] (accumulate [m 0 _ b (ipairs boxes)] (math.max m (. b a)))))]
                        (fail ctx (sub-path path :bounds)
                              (.. (case (values-text first.at) text (.. "with " text ", ") _ "")
                                  (bounds-message first.low first.on first.on-face? out.bounds box
                                                  (accumulate [spent? false _ c (ipairs crossings)] (or spent? c.spent?))))))))
            (case (custom.factor measured out.lipschitz at out.trust-lipschitz)
              (nil why) (fail ctx (sub-path path :lipschitz) why)
              k (do (set out.lipschitz k)
                    (set data.measured measured)
                    (set out.custom data))))))))

(fn check-node [ctx path o depth counter]
  (when (not= (type o) :table)
    (fail ctx path (.. "must be a node table like {:kind :sphere ...}, got " (describe-value o))))
  (set counter.n (+ counter.n 1))
  (when (> counter.n limits.max-nodes)
    (fail ctx path (.. "the scene has more than " limits.max-nodes " tree nodes")))
  (when (> depth limits.max-depth)
    (fail ctx path (.. "nested deeper than " limits.max-depth " nodes")))
  (when (= o.kind nil)
    (fail ctx path "missing :kind (see `love . --kinds` for the list)"))
  (when (not= (type o.kind) :string)
    (fail ctx (sub-path path :kind) (.. "must be a kind name like :sphere, got " (describe-value o.kind))))
  (let [prim (primitives.lookup o.kind)
        op (operations.lookup o.kind)
        desc (or prim op (when (= o.kind :custom) custom-spec))]
    (when (not desc)
      (fail ctx (sub-path path :kind)
            (.. "unknown kind " (text.keyword o.kind) (suggestion o.kind (all-kind-names))
                " (`love . --kinds` lists them all)")))
    (let [allowed (icollect [_ p (ipairs desc.params)] p.name)]
      (each [_ f (ipairs shorthand-fields)] (table.insert allowed f))
      (table.insert allowed :kind)
      (each [_ f (ipairs (or desc.extra-fields []))] (table.insert allowed f))
      (when op (table.insert allowed :children))
      (check-keys ctx path o allowed))
    (let [out {:kind o.kind :path (path->string path) :path-list path}]
      (each [_ f (ipairs shorthand-fields)]
        (let [v (. o f)]
          (when (not= v nil)
            (when (and (. modern-fields f) (not ctx.modern?))
              (fail ctx (sub-path path f)
                    "is read only by the modern lighting model: add :lighting {:model :modern} to the scene"))
            (tset out f (check ctx (sub-path path f) v (. shorthand-types f))))))
      (each [_ p (ipairs desc.params)]
        (let [v (. o p.name)]
          (tset out p.name (if (not= v nil) (check-param ctx (sub-path path p.name) v p)
                               p.optional? nil
                               p.required? (fail ctx (sub-path path p.name) p.missing)
                               (fresh p.default)))))
      (when (= desc custom-spec) (check-custom! ctx path o out))
      (when desc.check
        (let [(field reason) (desc.check out)]
          (when field (fail ctx (sub-path path field) reason))))
      (when op
        (let [children o.children
              [lo hi] desc.children
              cpath (sub-path path :children)]
          (when (or (not= (type children) :table) (= (next children) nil))
            (fail ctx cpath (.. "must be a list of " (if (= lo hi) (.. lo " node") (.. lo " or more nodes"))
                                ", got " (describe-value children))))
          (var last 0)
          (each [k _ (each-pair children)]
            (when (or (not= (type k) :number) (< k 1) (not= k (math.floor k)))
              (fail ctx cpath "must be a list [...] of nodes, not a table with named fields"))
            (set last (math.max last k)))
          (when (or (< last lo) (and hi (> last hi)))
            (fail ctx cpath (.. ":" o.kind " takes " (if (= lo hi) (.. "exactly " lo)
                                                        hi (.. lo " to " hi)
                                                        (.. lo " or more"))
                                " " (if (= hi 1) "child" "children") ", got " last)))
          (set out.children (fcollect [k 1 last]
                              (check-node ctx (sub-path cpath k) (. children k) (+ depth 1) counter)))))
      out)))

(fn check-object [ctx i o counter]
  (when (not= (type o) :table)
    (fail ctx [:objects i] (.. "must be a table like {:kind :sphere ...}, got " (describe-value o))))
  (if (and (= (type o.kind) :string) (grouped? o))
      (check-grouped ctx i o)
      (let [node (check-node ctx [:objects i] o 1 counter)]
        ;; What only lowering finds (a twist of an unbounded child) is reported here,
        ;; where the node's line is known; a tree that cannot be refused is lowered
        ;; once, by the plan.
        (when (lower.may-refuse? node)
          (case (lower.lower [node])
            (nil _ bad reason) (fail ctx bad.path-list reason)))
        {:kind node.kind :index i :tree node :path node.path})))

(fn validate [value ctx]
  (when (or (not= (type value) :table)
            (and (not= nil (. value 1)) (= nil (next value (length value)))))
    (fail ctx [] (.. "a scene file must evaluate to a table like {:objects [...]}, got "
                     (describe-value value))))
  (check-keys ctx [] value top-level-keys)
  (when (not= value.name nil) (check-name ctx value.name))
  (when (= value.objects nil)
    (fail ctx [:objects] "missing; a scene needs :objects [...] (it may be empty)"))
  (when (not= (type value.objects) :table)
    (fail ctx [:objects] (.. "must be a list of objects, got " (describe-value value.objects))))
  (var last 0)
  (each [k _ (each-pair value.objects)]
    (when (or (not= (type k) :number) (< k 1) (not= k (floor k)))
      (fail ctx [:objects] "must be a list [...] of objects, not a table with named fields"))
    (when (> k last) (set last k)))
  ;; Counted by the highest index, before anything else about the list (a hole in it
  ;; is refused just below, after this count, which bounds the search).
  (when (> last limits.max-objects)
    (fail ctx [:objects] (.. "has " last " objects; at most " limits.max-objects
                             " are allowed (remove " (- last limits.max-objects) ")")))
  ;; A nil in the list would hide every object after it from ipairs and length.
  (for [i 1 last]
    (when (= nil (. value.objects i))
      (fail ctx [:objects i] "must be a table like {:kind :sphere ...}, got nil")))
  (local light (check-section ctx :light value.light))
  (local lighting (check-lighting ctx value.lighting light))
  (set ctx.modern? (not= nil lighting))
  {:name (or value.name (: (ctx.file:match "([^/]+)$") :gsub "%.fnl$" ""))
   :file ctx.file
   :camera (check-section ctx :camera value.camera)
   : light
   : lighting
   :environment (if (= value.environment nil) (fresh default-environment)
                    (check ctx [:environment] value.environment :color))
   :render (check-section ctx :render value.render)
   :objects (let [counter {:n 0}]
              (icollect [i o (ipairs value.objects)] (check-object ctx i o counter)))})

(fn clean-fennel-message [msg file]
  ;; Fennel's parse and compile errors carry the file and line already; keep the first
  ;; line (the rest repeats the source with a caret) and strip the 'Parse error in' prefix.
  (let [first-line (or (msg:match "^[^\n]+") msg)]
    (let [msg (if (first-line:find "stack overflow" 1 true)
                  ;; Lua names the line only when the overflow happens in the scene's
                  ;; own code, not in a library call or the step hook: one message.
                  (.. file ": stack overflow")
                  (first-line:find file 1 true) first-line
                  (.. file ": " first-line))
          ident (or (msg:match "unknown identifier: ([%w_]+)")
                    (msg:match "expected local ([%w_]+)"))]
      (if ident
          (.. msg " (scene files are data: only math, numbers, strings and tables are available)")
          ;; An error inside the compiler itself (input it does not expect): say so
          ;; rather than show a line of fennel.lua.
          (msg:find "fennel[%w/%.]*:%d+:")
          (.. file ": the file is not a scene Fennel can read ("
              (or (msg:match "fennel[%w/%.]*:%d+: (.*)$") msg) ")")
          msg))))

(local max-message 400)   ; bytes of one message shown

(fn safe-message [msg]
  "A loader message as shown anywhere: escaped (no control characters or broken
UTF-8 from a hostile file or path) and at most a few lines long."
  (text.escape msg max-message))

(fn evaluate [source file rec]
  "Check, compile and run scene `source`, recording its parameters in `rec`: true,
the value it evaluates to, its parsed forms and the checked text; or nil and a
message."
  (let [env (doto (sandbox.safe-env) (tset :param (params.param-function rec)))
        allowed (doto (icollect [k (each-pair env)] k) table.sort)]
    (case (sandbox.check-source source file)
      (nil msg) (values nil msg)
      source (let [forms (sandbox.parse source file)]
               (case (and forms (sandbox.check-forms forms file))
                 msg (values nil msg)
                 _ (case (sandbox.compile source file allowed)
                     (nil msg) (values nil (if (sandbox.sandbox-error? msg)
                                               (sandbox.error-message msg)
                                               (clean-fennel-message
                                                (sandbox.error-message msg) file)))
                     code (case ((or _G.loadstring load) code (.. "@" file))
                            (nil err) (values nil (clean-fennel-message err file))
                            chunk (let [(ok? value) (sandbox.run chunk file env)]
                                    (if ok? (values true value forms source env)
                                        (sandbox.sandbox-error? value)
                                        (values nil (sandbox.error-message value))
                                        (values nil (clean-fennel-message
                                                     (sandbox.error-message value) file)))))))))))

(fn validated [value ctx]
  "The scene `value` validated with `ctx` (see `validate`), or nil and a message."
  (let [(ok? result) (pcall validate value ctx)]
    (if ok?
        (do (when (> (length ctx.animated) 0)
              (set result.animated ctx.animated))
            result)
        (and (= (type result) :table) result.scene-error)
        (values nil (safe-message result.scene-error))
        (error result))))

(fn too-large [file limit]
  (string.format "%s: the file is over %d bytes (%s), the most a scene file may have; make many objects with a loop, like (fcollect [i 1 n] {:kind :sphere ...})"
                 file limit (if (< limit (* 1024 1024)) (.. (/ limit 1024) " KB")
                                (.. (/ limit 1024 1024) " MB"))))

(fn read-data [source file]
  "Scene `source` read as plain data (src/scene/data.fnl), no compiler and no
sandbox: :data, the value and the text read (a byte order mark dropped); or :code
when it is not plain data and goes to the compiler (a file within the size limit of
code: whatever it holds, it then loads as it always did); or nil and a message."
  (let [limits sandbox.limits
        source (if (= (source:sub 1 3) "\239\187\191") (source:sub 4) source)
        size (length source)]
    (if (> size limits.data-bytes) (values nil (too-large file limits.data-bytes))
        (case (sandbox.check-encoding source file)
          msg (if (<= size limits.file-bytes) :code (values nil msg))
          _ (case (data.read source {:max-depth limits.nesting
                                     :max-memory-mb limits.data-memory-mb})
              (nil kind why pos)
              (if (<= size limits.file-bytes) :code
                  (= why :too-deep) (values nil (sandbox.nesting-message file (sandbox.nesting-line source)))
                  (= kind :refused) (values nil (.. file ":" (data.line-at source pos) ": " why))
                  (values nil (.. file ":" (data.line-at source pos) ": the file is over "
                                  limits.file-bytes " bytes (" (/ limits.file-bytes 1024)
                                  " KB), the most for a scene file with code, and this is not plain data ("
                                  why "); a file of plain data (numbers, strings, :keywords, true, false, [...] and {...}) may have up to "
                                  (/ limits.data-bytes 1024 1024) " MB")))
              value (values :data value source))))))

(fn load-data [source ?file]
  "Scene `source` loaded when it is plain data (see read-data): the scene, or nil and
a message; or false when it is code (load it with load-string, in the worker)."
  (let [file (or ?file "scene")]
    (case (read-data source file)
      :code false
      (:data value text)
      (validated value {: file :source text :animated [] :time-budget {:left frame-steps}
                        :ast-fn #(data.read text {:positions? true :path $1})})
      (nil msg) (values nil (safe-message msg)))))

(fn load-code [source file ?options]
  (let [rec (params.collector (?. ?options :overrides))
        (ok? value forms checked-source env) (evaluate source file rec)
        (sites-ok? site-err) (if (> (length rec.list) 0) (params.sites source file) true)]
    (if (and (not ok?) rec.failed)
        (values nil (safe-message (.. file ":" (or (params.failure-line source file rec) "?") ": "
                                      rec.failed.message)))
        (not ok?)
        (values nil (safe-message value))
        (not sites-ok?)
        (values nil (safe-message site-err))
        ;; Field lines come from the last form: the table the file evaluates to.
        ;; :sliders: a custom node's parameter given by one is checked over its range.
        ;; :measure: a test's count of the measures (src/sdf/custom.fnl's by default).
        (case (validated value {: file :source checked-source :ast (and forms (. forms (length forms)))
                                : forms : env :animated [] :time-budget {:left frame-steps}
                                :sliders rec.by-name :measure (?. ?options :measure)})
          (nil msg) (values nil msg)
          result (do (when (> (length rec.list) 0)
                       (set result.params rec.list)
                       (set result.source source))
                     result)))))

(fn load-string [source ?file ?options]
  "Evaluate scene `source` in a sandbox and validate it.
Returns the scene (plain data, defaults filled in) or nil and a message
'file:line: field: reason'. A file of plain data is read without the compiler (see
read-data). `?options.overrides` maps parameter names to the values
their (param ...) calls give instead of the file's; the scene's :params lists them
(see src/scene/params.fnl) and its :source is the text, to load it again with others.
`?options.measure` measures custom nodes' factors in place of custom.measure (a
test's count of its calls)."
  (let [file (or ?file "scene")]
    (case (load-data source file)
      false (load-code source file ?options)
      (nil msg) (values nil msg)
      scene scene)))

(fn target-of [scene path]
  ;; The table and key in the validated scene that `path` (a field path of the file)
  ;; names: the same, but that a tree object's nodes sit under its :tree.
  (var t scene)
  (for [i 1 (- (length path) 1)]
    (set t (. t (. path i)))
    (when (and (= i 2) (= (. path 1) :objects) t.tree) (set t t.tree)))
  (values t (. path (length path))))

(fn animated? [scene]
  "True when some value of `scene` is a function of time."
  (not= nil scene.animated))

(fn animate [scene t]
  "Set every function-of-time value of `scene` (in place) to its value at time `t`
(seconds), checked as at load. Returns true, or nil and a message 'file:line: field:
reason' (a value out of range, a function that fails or runs too long)."
  ;; One budget for all of them (see frame-steps).
  (let [budget {:left frame-steps}
        (ok? err) (pcall (fn []
                           (each [_ a (ipairs (or scene.animated []))]
                             (set a.checker-ctx.time-budget budget))
                           (each [_ a (ipairs (or scene.animated []))]
                             (let [v (a.checker (time-call (. a :checker-ctx) a.path a.f t) t)
                                   (target key) (target-of scene a.path)]
                               (tset target key v)))))]
    (if ok? true
        (and (= (type err) :table) err.scene-error) (values nil (safe-message err.scene-error))
        (error err 0))))

(fn read-capped [path]
  "The text of the file at `path` (see files.read-user), reading at most one byte past
the size limit (so /dev/zero or a huge file costs nothing)."
  (files.read-user path (+ sandbox.limits.data-bytes 1)))

(fn load-file [path ?read ?options]
  "Read and load the scene file at `path` (see load-string, which takes `?options`).
`?read` reads a file's text (default: io.open, at most the size limit and a byte), so
the app can read through love.filesystem."
  (let [(source err) ((or ?read read-capped) path)]
    (if source
        (load-string source path ?options)
        (values nil (safe-message (.. path ": cannot read the scene file: "
                                      (tostring (or err "no such file"))))))))

(fn defaults []
  "A copy of the default settings, by section (for docs and tests)."
  (collect [name spec (each-pair sections)]
    name (collect [field f (each-pair spec)] field f.default)))

(fn limits-of-files []
  "The sandbox's limits (file size, nesting, steps, memory)."
  sandbox.limits)

{: load-string : load-data : load-file : read-capped : animate : animated? : limits-of-files : defaults : limits : default-environment
 : safe-message : target-of : time-text : validated
 : hit-tests : normal-methods}
