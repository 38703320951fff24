;; Drawing strategies: how a tape object is drawn. Lowering (src/sdf/lower.fnl) gives
;; every tape object a :strategy, the name of one descriptor file in
;; src/sdf/strategies/, found by listing that folder as primitives and lighting
;; features are. Every consumer (the GLSL and Lua emitters, the bounds, the CPU
;; reference, --tree) reaches an object through its strategy's descriptor and never
;; asks which strategy that is: drawing a new way is one new file.
;;
;; A descriptor:
;;   :name      keyword, the :strategy lowering writes; :doc one line
;;   :count     (fn [o]) -> the objects it draws (an object number each)
;;   :takes?    optional (fn [count]) -> whether it draws `count` scene objects of one
;;              structure (lower.fnl: equal keys, the same code but for their values);
;;              lowering asks those that have it, by :rank (lowest first), and gives
;;              the objects to the first that takes them. A strategy without it is
;;              chosen elsewhere (a field: by the plan)
;;   :rank      with :takes?: its place in that order
;;   :gathers?  with :takes?: true to draw them as one tape object whose members' rows
;;              go one after another in the instance bank (its :instances {:count
;;              :base :stride}), false for one tape object each, rows in the tape's
;;              bank
;;   :key       with :takes?: (fn [key count]) -> its part of the tape's structure key
;;   :folds?    whether fold! (values as constants, lower.fnl) writes its rows into the
;;              code (an instance group's stay in its bank; a field has no code)
;;   :marched?  (fn [o]) -> whether a bounded march steps by its distance (mapFinite):
;;              not a half-space (met in closed form) nor a field (its grid is walked)
;;   :infos     (fn [o]) -> its objects' lowered root infos, or nil when they have
;;              none (a field's members)
;;   :describe  (fn [o]) -> what --tree adds after its root's kind
;;   :glsl      the lines it gives each of the shader's queries (emit-glsl.fnl's
;;              context cx; `first`, the number of the tape's first object):
;;              :distance (fn [cx o]) map's term (mapFinite's with cx.finite? true;
;;              mapSome's with cx.finite? a GLSL expression: emit-glsl.some-terms);
;;              :color (fn [cx o ?first mirrors? modern?]) mapColor's (with ?first it
;;              sets gObject); :object (fn [cx o first mirrors? modern?])
;;              mapObject(p, only, skip, materials, color)'s: object `only` alone,
;;              or with `all` (only -1) every object but `skip`, or with `materials`
;;              mapColor's query (emit-glsl's either-tail writes a tree's code once
;;              for all; either-terms wraps two forms); :gradient (fn [cx o
;;              first action]) its exact normal (nil: none); :planes (fn [cx o])
;;              planesHit's (nil: not a half-space); :exact? (fn [o]) whether it has an
;;              exact normal in closed form
;;   :lua       (fn [tape o what banks into]) adds its CPU evaluators (emit-lua.fnl's
;;              compile: `what` is :distance, :material, :gradient or :estimate) to the
;;              list `into`, one per object, and returns the Lua source it compiled, if
;;              any
;;   :spheres   (fn [plan o at out]) adds the bounding spheres a bounded march tests
;;              ([centre radius], false for an object that has none) to `out`; `at`
;;              is the number of plan.objects before its first. Returns the count
;;              after its objects (src/render/bounds.fnl)
;;   :run       (fn [plan o run]) fills the CPU reference's run of its objects
;;              ({:first :last} numbers in plan.objects) with what its queries need
;;   :uniforms  optional (fn [plan o cam-pos]) -> its own uniforms (src/render/uniforms.fnl)
;;   :shader    optional parts of the shader of its own (src/render/codegen.fnl), each
;;              given the plan, the object and the chunk system's fill: :functions (fn
;;              [plan o fill defined]) -> sections of function definitions (those not
;;              yet `defined`, added to it); :gradients (the same) -> lines of the
;;              gradients its exact normals call, or nil; :sections (fn [plan o fill])
;;              -> a section after the hit test
;;   :grid-boxes optional (fn [o number]) -> the boxes of its objects and its bank's
;;              layout ({:base :stride}) when a grid is to hold them (then it marks
;;              itself grid `number`, from 0), or nil (src/render/plan.fnl's grids-of)
;;   :bank-in-texture! optional (fn [o]): the instance bank is read from a texture
;;   :reference {:min (fn [run d x y z skip tape-distance draw ?dx ?dy ?dz]) -> d
;;              lowered by its objects but `skip`; :color (fn [run x y z d best r g b
;;              mirror rough emit tape-distance tape-material modern?]) -> the same
;;              after its objects, the nearest's material winning; :near (fn [run x y
;;              z reach tape-distance]) -> how many come within reach}
;;              (src/reference/distance.fnl)
;;   :members   optional (fn [o]) -> the tape objects it stands for, in order (the
;;              interpreter's): the CPU reference queries each through its own
;;              strategy (`queried`), so such a strategy needs no :run nor :reference

;; `pairs` under another name: a loop over `pairs` by that name is LuaJIT's ITERN,
;; which Debian 12's LuaJIT ends early once despecialised (see src/util/wire.fnl).
(local each-pair pairs)

(local files (require :src.util.files))

(local dir "src/sdf/strategies")

(fn check-descriptor [d file]
  (fn need [ok? what] (assert ok? (.. file ": strategy " what)))
  (need (= (type d.name) :string) "needs a :name")
  (need (= (type d.doc) :string) "needs :doc")
  (each [_ key (ipairs [:count :marched? :infos :describe :lua :spheres])]
    (need (= (type (. d key)) :function) (.. "needs :" key)))
  (need (or d.members (= (type d.run) :function)) "needs :run (or :members)")
  (need (= (type d.folds?) :boolean) "needs :folds?")
  (need (= (type d.glsl) :table) "needs :glsl")
  (each [_ key (ipairs [:distance :color :object :gradient :planes :exact?])]
    (need (= (type (. d.glsl key)) :function) (.. "needs :glsl :" key)))
  (when (not d.members)
    (need (= (type d.reference) :table) "needs :reference (or :members)")
    (each [_ key (ipairs [:min :color :near])]
      (need (= (type (. d.reference key)) :function) (.. "needs :reference :" key))))
  d)

;; The descriptors by name, loaded on first use: they require the emitters, which
;; reach objects through this module.
(local loaded {})

(fn by-name []
  (when (not (next loaded))
    (each [_ file (ipairs (assert (files.list-project dir)))]
      (let [base (file:match "^(.-)%.fnl$")]
        (when base
          (let [d (check-descriptor (require (.. "src.sdf.strategies." base)) (.. dir "/" file))]
            (tset loaded d.name d))))))
  loaded)

(fn all []
  "Every strategy's descriptor, sorted by name."
  (doto (icollect [_ d (each-pair (by-name))] d)
    (table.sort (fn [a b] (< a.name b.name)))))

(fn of [o]
  "The descriptor of tape object `o`'s strategy (its :strategy)."
  (or (. (by-name) o.strategy)
      (error (.. "no drawing strategy " (tostring o.strategy) " in " dir))))

(fn chosen-in-lowering []
  "The strategies lowering chooses among for objects of one structure (those with
:takes?), by :rank."
  (doto (icollect [_ d (ipairs (all))] (when d.takes? d))
    (table.sort (fn [a b] (< a.rank b.rank)))))

(fn count [o]
  "How many objects tape object `o` draws (an object number each)."
  ((. (of o) :count) o))

(fn queried [tape]
  "The objects of `tape` the CPU reference queries, in order: each tape object, or
the ones it stands for (its strategy's :members), their object numbers the same."
  (let [out []]
    (each [_ o (ipairs tape.objects)]
      (case (. (of o) :members)
        members (each [_ m (ipairs (members o))] (table.insert out m))
        _ (table.insert out o)))
    out))

{: all : of : count : chosen-in-lowering : queried}
