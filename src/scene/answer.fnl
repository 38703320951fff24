;; The main process's check of the scene worker's answers (src/scene/worker.fnl). The
;; worker runs a scene's code; code that escaped the sandbox there, or another program
;; in its place, could answer anything the wire format carries (src/util/wire.fnl:
;; tables at most 100 deep, 256 MB). So an answer is input like a scene file, and it is
;; checked by the loader's own validation (src/scene/load.fnl), not by a second schema:
;;
;; - the scene is turned back into what a file writes (a grouped object without its
;;   :index, a tree object as its tree, nodes without :path and :path-list, a custom
;;   node's data set aside) and validated as a file is, with the same tables of
;;   sections, primitives and operations, limits and messages; what the app uses is the
;;   loader's output, so nothing the worker added passes;
;; - a custom node's texts are checked as the lowering checks them (only what the
;;   translator writes, their digest) before the loader takes them in place of a
;;   translation, with the worker's measured Lipschitz factor (a number in range);
;; - each value the worker keeps a function of time for is given back as one, so the
;;   loader checks that its field may change with time and makes the checker each
;;   frame's values go through (`check-values`);
;; - the parameters are recorded again by the loader's own `param` (src/scene/params.fnl),
;;   and the scene's text is the one the app sent.
;;
;; Every refusal reads "FILE: the scene worker's answer was refused: FIELD: reason".

(local load (require :src.scene.load))
(local params (require :src.scene.params))
(local sandbox (require :src.scene.sandbox))
(local custom (require :src.sdf.custom))
(local translate (require :src.sdf.translate))
(local primitives (require :src.sdf.primitives))
(local operations (require :src.sdf.operations))

(local max-depth load.limits.max-depth)
;; A field's path: :objects, an index, then :children and an index per level, a
;; parameter's name and the field (the loader's deepest: a custom node's :params).
(local max-path (+ 6 (* 2 max-depth)))
(local max-names 64)   ; a custom function's parameters (the loader's have far fewer)
;; The check of a custom node's measured factor: custom.measure as if the function
;; cost this many times more (an 8^3 grid, a thirtieth of the refinement: a few ms
;; where the worker's takes 10 to 60), at each value the worker measured. Its samples
;; are not the worker's, so it may find a steeper place the worker's missed: only a
;; slope above the worker's factor (at least 1) by `spot-tolerance` is a forgery.
(local spot-thinning 30)
(local spot-tolerance 1.5)
;; Its verdicts by function, bounds and factor, kept across loads (at most spot-kept,
;; then cleared): a slider's drag loads again at every move, with the factor the
;; worker measured over the slider's whole range, and checking it at every value took
;; scenes/custom.fnl's drag from 11 to 56 ms of the app's CPU. A factor checked once
;; is checked; another one for the same function is checked anew.
(local spot-verdicts {:n 0 :entries {}})
(local spot-kept 64)

(fn spot-check [data cpu bounds args cost]
  "nil when the worker's measured factor of custom `data` holds at `args` by the
thinner measure (see spot-thinning), or held at the values it was first checked
at; else the refusal's reason."
  (let [key (.. data.lua "\n" (table.concat bounds " ") "\n" (string.format "%.17g" data.measured))
        kept (. spot-verdicts.entries key)]
    (if (not= nil kept) (or kept nil)
        (let [verdict (case (custom.measure cpu bounds args (* spot-thinning (math.max 1 (or cost 1))))
                        (spot [x y z]) (when (> spot (* spot-tolerance (math.max 1 data.measured)))
                                         (string.format "a custom node: its measured factor %.3g is below the slope %.3g found here at [%.3g %.3g %.3g] (refused)"
                                                        data.measured spot x y z)))]
          (when (>= spot-verdicts.n spot-kept)
            (set spot-verdicts.entries {})
            (set spot-verdicts.n 0))
          (tset spot-verdicts.entries key (or verdict false))
          (set spot-verdicts.n (+ spot-verdicts.n 1))
          verdict))))

(local type type)
;; `pairs` under another name: a loop over `pairs` by that name is LuaJIT's ITERN,
;; which Debian 12's LuaJIT ends early once despecialised (see src/util/wire.fnl).
(local each-pair pairs)
(local ipairs ipairs)

(fn finite? [v]
  (and (= (type v) :number) (= v v) (not= v math.huge) (not= v (- math.huge))))

(fn prefix [file]
  (.. file ": the scene worker's answer was refused"))

(fn refused [file reason]
  (load.safe-message (.. (prefix file) ": " reason)))

(fn reword [file msg]
  ;; A loader message for ctx.file = (prefix file), without the line a custom node's
  ;; message names (a line of this file, not of the scene's).
  (let [p (prefix file)]
    (if (= (msg:sub 1 (length p)) p)
        (.. p (: (msg:sub (+ 1 (length p))) :gsub "^:%-?%d+:" ":"))
        msg)))

(fn list? [t n]
  ;; `t` is a list of `n` values (1..n, no other key).
  (and (= (type t) :table)
       (accumulate [ok? true k (each-pair t)]
         (and ok? (= (type k) :number) (>= k 1) (<= k n) (= k (math.floor k))))
       (or (= n 0) (not= nil (. t n)))
       (= (length t) n)))

;;; Custom nodes: the worker's texts in place of a translation

(fn name? [s]
  (and (= (type s) :string) (<= 1 (length s) 80) (not (s:find "[%c%s]"))))

(fn translation [data]
  ;; What custom.capture gives, from the worker's data `data`: the texts, checked as
  ;; the lowering checks them (custom.check-data: the translator's GLSL and Lua, and
  ;; the digest), with the GLSL named as the translator names it; or nil and why not.
  (case (custom.check-data data)
    why (values nil (.. "a custom node: " why " (refused)"))
    _ (if (not (and (list? data.params (length data.params)) (<= (length data.params) max-names)
                    (accumulate [ok? true _ n (ipairs data.params)] (and ok? (name? n)))
                    (= (length data.params)
                       (accumulate [c 0 _ (each-pair (collect [_ n (ipairs data.params)] n true))] (+ c 1)))))
          (values nil "a custom node: its parameters are not a list of distinct names (refused)")
          (not (and (finite? data.cost) (<= 0 data.cost translate.limits.cost)))
          (values nil (.. "a custom node: its cost is not a number from 0 to " translate.limits.cost " (refused)"))
          (not (and (finite? data.measured) (<= 0 data.measured load.limits.world)))
          (values nil "a custom node: its measured factor is not a number from 0 to 1e7 (refused)")
          {:glsl (pick-values 1 (data.glsl:gsub data.glsl-name "sdCustom"))
           :lua data.lua :params data.params :cost data.cost})))

;;; The answer as a file writes it

(fn as-written! [node depth customs]
  ;; Tree node `node` (in place) as a file writes it. Deeper than the loader allows,
  ;; it is left as it is: the loader refuses it there first.
  (when (and (= (type node) :table) (<= depth max-depth))
    (set node.path nil)
    (set node.path-list nil)
    (when (= node.kind :custom)
      ;; The loader wants a function for :distance: one that stands for the data.
      (let [data node.custom
            f (fn [] data)]
        (set node.custom nil)
        (set node.distance f)
        (tset customs f data)))
    (when (= (type node.children) :table)
      (each [_ c (each-pair node.children)] (as-written! c (+ depth 1) customs)))))

(fn objects-as-written! [objects customs]
  ;; The objects (in place) as a file writes them; or the field and why not.
  (var bad nil)
  (each [i o (ipairs objects) &until bad]
    (when (= (type o) :table)
      (if (not= o.index i) (set bad [[:objects i :index] (.. "must be " i)])
          (= nil o.tree) (set o.index nil)
          (not= (type o.tree) :table) (set bad [[:objects i :tree] "must be a node table"])
          (not= o.kind o.tree.kind) (set bad [[:objects i :kind] "must be its tree's kind"])
          (do (as-written! o.tree 1 customs)
              (tset objects i o.tree)))))
  bad)

(fn path-text [path]
  (table.concat (icollect [i k (ipairs path)]
                  (if (= (type k) :number) (.. "[" k "]") (= i 1) k (.. "." k)))))

(fn place-functions! [scene paths]
  ;; Each value at `paths` (the worker's functions of time) replaced by a function
  ;; that gives it, for the loader to check as one; nil, or why not.
  (var bad nil)
  (each [i p (ipairs paths) &until bad]
    (if (not (and (list? p (length p)) (<= 1 (length p) max-path)
                  (accumulate [ok? true _ k (ipairs p)]
                    (and ok? (or (name? k) (and (finite? k) (>= k 1) (= k (math.floor k))))))))
        (set bad (.. "animated[" i "]: not the path of a field"))
        (do (var t scene)
            (for [j 1 (- (length p) 1)]
              (set t (when (= (type t) :table) (. t (. p j)))))
            (let [k (. p (length p))
                  v (when (= (type t) :table) (. t k))]
              (if (or (= v nil) (= (type v) :function))
                  (set bad (.. "animated[" i "]: " (path-text p) " is not a value of the scene"))
                  (tset t k (fn [] v)))))))
  bad)

(fn same-path? [a b]
  (and (= (length a) (length b))
       (accumulate [ok? true j k (ipairs a)] (and ok? (= k (. b j))))))

;;; Directions: the loader divides a direction by its length, and a unit vector divided
;;; again may move by a unit in the last place. The worker's vector is kept where it is
;;; the loader's within rounding, so a scene is the same whichever process loaded it.

(fn rounding-of [checked given]
  ;; `given` (or what it stands for: see place-functions!) when it is three numbers
  ;; within rounding of `checked`'s, else `checked`.
  (local raw (if (= (type given) :function) (given) given))
  (if (and (= (type checked) :table) (= (type raw) :table) (= 3 (length checked))
           (accumulate [ok? true k c (ipairs checked)]
             (and ok? (finite? (. raw k)) (<= (math.abs (- (. raw k) c)) 1e-15))))
      [(. raw 1) (. raw 2) (. raw 3)]
      checked))

(fn keep-directions! [out given depth]
  ;; Tree node `out` (the loader's) given as `given` (the worker's, as written).
  (when (and (= (type given) :table) (<= depth max-depth))
    (let [desc (or (primitives.lookup out.kind) (operations.lookup out.kind))]
      (each [_ p (ipairs (or (?. desc :params) []))]
        (when (= p.type :direction)
          (tset out p.name (rounding-of (. out p.name) (. given p.name))))))
    (each [i c (ipairs (or out.children []))]
      (keep-directions! c (?. given :children i) (+ depth 1)))))

;;; Parameters

(fn checked-params [file list]
  ;; The worker's parameters recorded again by the loader's own `param`: the list, or
  ;; nil and a message.
  (if (not (list? list (length list)))
      (values nil (refused file "params: not a list"))
      (let [overrides (collect [_ p (ipairs list)]
                        (when (and (= (type p) :table) (= (type p.name) :string))
                          (values p.name {:value p.value :base p.default})))
            rec (params.collector overrides)
            call (params.param-function rec)]
        (var err nil)
        (each [i p (ipairs list) &until err]
          (if (not= (type p) :table) (set err (.. "params[" i "]: not a parameter"))
              (let [opts (if (or (not= nil p.min) (not= nil p.max)) {:min p.min :max p.max})
                    (ok? why) (pcall call p.name p.default opts)
                    q (. rec.list i)]
                (if (not ok?) (set err (.. "params[" i "]: " (tostring why)))
                    (or (not q) (not= q.name p.name) (not= q.kind p.kind))
                    (set err (.. "params[" i "].kind: not the kind of its value"))
                    (not (params.same-value? q.value p.value))
                    (set err (.. "params[" i "].value: not a value of the parameter"))))))
        (if err (values nil (refused file err)) rec.list))))

;;; Answers

(fn check-scene [answer file source]
  "The scene of the worker's `answer` ({:scene :animated}) to the load of `source`
(scene `file`), checked as the loader checks a file and built by it: the scene the
app uses (its :animated lists the paths of the worker's functions of time, with the
loader's checker of each), or nil and a message 'FILE: the scene worker's answer
was refused: FIELD: reason'. Takes the answer's tables apart."
  (let [scene answer.scene
        paths (or answer.animated [])
        customs (setmetatable {} {:__mode :k})
        ctx {:file (prefix file) :source "" :animated []}]
    (var current nil)
    ;; A refusal with a line, as custom.capture gives it (reword drops it).
    (set ctx.capture
         (fn [f]
           (case (. customs f)
             nil (values nil "a custom node's distance is not the worker's (refused)" 0)
             data (case (translation data)
                    (nil why) (values nil why 0)
                    t (do (set current data) t)))))
    ;; The worker's measured factor, checked here by a thinner measure of the same
    ;; function (see spot-thinning): a factor forged low would let the shader's
    ;; steps pass the surface.
    (var forged-factor nil)
    (set ctx.measure
         (fn [cpu bounds args cost]
           (when (= nil forged-factor)
             (set forged-factor (spot-check current cpu bounds args cost)))
           (values current.measured [0 0 0])))
    (if (not= (type scene) :table) (values nil (refused file "the scene is not a table"))
        (not= scene.file file) (values nil (refused file "file: not the file that was sent"))
        (not= (type scene.name) :string) (values nil (refused file "name: missing"))
        (not= (type scene.objects) :table) (values nil (refused file "objects: not a list"))
        (not (list? paths (length paths))) (values nil (refused file "animated: not a list"))
        (case (objects-as-written! scene.objects customs)
          [path why] (values nil (refused file (.. (path-text path) ": " why)))
          _ (let [given-params scene.params]
              (set scene.file nil)
              (set scene.params nil)
              (set scene.source nil)
              (when (> (length paths) 0) (set ctx.env (sandbox.safe-env)))
              (case (place-functions! scene paths)
                (where why (= (type why) :string)) (values nil (refused file why))
                _ (case (load.validated scene ctx)
                    (nil msg) (values nil (reword file msg))
                    (where _ forged-factor) (values nil (refused file forged-factor))
                    out (let [animated (or out.animated [])
                              (plist perr) (if (= nil given-params) []
                                               (checked-params file given-params))]
                          (if (not plist) (values nil perr)
                              (or (not= (length animated) (length paths))
                                  (not (accumulate [ok? true i a (ipairs animated)]
                                         (and ok? (same-path? a.path (. paths i))))))
                              (values nil (refused file "animated: not the scene's functions of time, in order"))
                              (do (set out.file file)
                                  (each [i l (ipairs (or (?. out.lighting :lights) []))]
                                    (set l.direction (rounding-of l.direction (?. scene.lighting :lights i :direction))))
                                  (each [i o (ipairs out.objects)]
                                    (when o.tree (keep-directions! o.tree (. scene.objects i) 1)))
                                  (set out.animated
                                       (when (> (length animated) 0)
                                         (icollect [_ a (ipairs animated)] {:path a.path :checker a.checker})))
                                  (when (> (length plist) 0)
                                    (set out.params plist)
                                    (set out.source source))
                                  out))))))))))

(fn check-values [scene vals]
  "The worker's `vals` of `scene`'s functions of time (one per entry of its
:animated, in order), each checked as at load: the list of checked values, or nil
and a message naming the field."
  (let [n (length scene.animated)]
    (if (not (list? vals n))
        (values nil (refused scene.file (.. "the values of the functions of time: not a list of " n)))
        (do (var err nil)
            (let [out (icollect [i a (ipairs scene.animated) &until err]
                        (let [(ok? v) (pcall a.checker (. vals i))]
                          (if ok? (rounding-of v (. vals i))
                              (do (set err (if (and (= (type v) :table) v.scene-error)
                                               (reword scene.file (load.safe-message v.scene-error))
                                               (refused scene.file (.. "animated[" i "]: not a value"))))
                                  nil))))]
              (if err (values nil err) out))))))

{: check-scene : check-values}
