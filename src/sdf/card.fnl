;; The scene language's reference card (`love . --kinds`, and the table in docs/scenes.md):
;; every primitive and operation, one per line, with its parameters and its class.

(local primitives (require :src.sdf.primitives))
(local operations (require :src.sdf.operations))

(fn default-text [v]
  (if (= (type v) :table) (.. "[" (table.concat (icollect [_ x (ipairs v)] (tostring x)) " ") "]")
      (= (type v) :string) (.. ":" v)
      (tostring v)))

(fn param-text [p]
  (.. ":" p.name (if p.optional? " (optional)" (.. " " (default-text p.default)))))

(fn params-text [d]
  (table.concat (icollect [_ p (ipairs d.params)] (param-text p)) ", "))

(fn primitive-class [d]
  (if (> d.lipschitz 1) (string.format "bound, Lipschitz %g" d.lipschitz)
      (= d.class :exact) "exact"
      "bound"))

(fn children-text [d]
  (let [[lo hi] d.children]
    (if (= lo hi) (.. lo " child") (.. lo "+ children"))))

(fn lines []
  "The card's lines: primitives, then operations."
  (let [out [(.. "primitives (" (length primitives.all) "): kind  class  parameters with defaults")]]
    (each [_ d (ipairs primitives.all)]
      (table.insert out (.. "  :" d.kind "  " (primitive-class d) "  " (params-text d))))
    (table.insert out (.. "operations (" (length operations.all) "): kind  children  class  parameters"))
    (each [_ name (ipairs (operations.kind-names))]
      (let [d (operations.lookup name)]
        (table.insert out (.. "  :" d.kind "  " (children-text d) "  "
                              d.class-doc "  " (params-text d)))))
    (table.insert out "custom: {:kind :custom :distance (fn [x y z ...] ...) :bounds [hx hy hz] :params {...} :lipschitz k (optional) :trust-lipschitz true (optional: use k below the measure)}, a distance function in Fennel (docs/scenes.md, Custom nodes)")
    (table.insert out "every node also takes :pos [x y z], :rotate [x y z] degrees, :scale s, :color [r g b], :mirror 0..1")
    out))

(fn markdown []
  "The card as Markdown table rows, for docs/scenes.md."
  (let [out ["| kind | class | parameters (defaults) | what it is |" "|---|---|---|---|"]]
    (each [_ d (ipairs primitives.all)]
      (table.insert out (.. "| `:" d.kind "` | " (primitive-class d) " | " (params-text d) " | " d.doc " |")))
    (each [_ name (ipairs (operations.kind-names))]
      (let [d (operations.lookup name)]
        (table.insert out (.. "| `:" d.kind "` (" (children-text d) ") | "
                              d.class-doc " | " (params-text d) " | " d.doc " |"))))
    out))

{: lines : markdown}
