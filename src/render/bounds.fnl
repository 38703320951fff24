;; Bounds the marcher tests a ray against before it marches, so that it marches only the
;; objects it may hit, where it may hit them: a bounding sphere for every finite object,
;; and the half-spaces (ground planes) met in closed form. A ray then marches only the
;; finite objects, only over the span where it is inside some object's bound, and stops
;; at the nearest plane. Pure: runs under plain LuaJIT; the GLSL
;; (shaders/pipeline/march.glsl, bounded) and the CPU reference (src/reference.fnl)
;; follow the same rules.

;; From this radius on a sphere loses float32 precision near its surface.
(local large-radius (. (require :src.sdf.large-sphere) :radius))
(local strategies (require :src.sdf.strategies))

(fn length3 [[x y z]] (math.sqrt (+ (* x x) (* y y) (* z z))))

(fn object-sphere [o info]
  "World centre and radius of a sphere holding scene object `o`, whose lowered root
info (see src/sdf/lower.fnl) is `info`, or nil when it has none: an infinite node, or
a large sphere (src/sdf/large-sphere.fnl), whose bound would lose float32 precision
near its surface."
  ;; The root is the translation of the object's placement (its :pos, or the node
  ;; itself when it is a translation); its child's bounds are half extents about that
  ;; point. Their sphere grows with the distance from the root to what it holds: a
  ;; group without a :pos whose children stand 1e6 out gets one 1e6 wide about the
  ;; origin, whose ray test loses its span in float32 (as a sphere of radius 1000 or
  ;; more loses its surface). From that radius on, the sphere about the child's box
  ;; ({:lo :hi} about the root) holds it instead.
  (let [node (or o.tree o)
        child (when (not info.large?) (. info.children 1))
        [px py pz] (or node.pos (and (= node.kind :translate) node.offset) [0 0 0])
        b (and child child.bounds)
        box (and child child.box)]
    (if (and b box (>= (length3 b) large-radius))
        (let [{: lo : hi} box]
          [[(+ px (* 0.5 (+ (. lo 1) (. hi 1))))
            (+ py (* 0.5 (+ (. lo 2) (. hi 2))))
            (+ pz (* 0.5 (+ (. lo 3) (. hi 3))))]
           (length3 (fcollect [i 1 3] (* 0.5 (- (. hi i) (. lo i)))))])
        b [[px py pz] (or child.radius (length3 b))])))

(fn grid-sphere [g]
  "The sphere about a grid's box (src/sdf/grid.fnl): it holds every member."
  (let [[lx ly lz] g.lo
        [sx sy sz] g.size]
    [[(+ lx (* 0.5 sx)) (+ ly (* 0.5 sy)) (+ lz (* 0.5 sz))]
     (* 0.5 (length3 g.size))]))

(fn finite-spheres [plan]
  "The bounding spheres ([centre radius], or false for an object that has none) of the
objects a bounded plan marches by them, each tape object's by its drawing strategy's
:spheres (src/sdf/strategies/): every object's (an instance group's members each)
but the half-spaces (met in closed form; see lower.fnl); one for an instance group
with a grid, about its grid; not a field's (its grid bounds them; see
src/render/field.fnl). plan.objects holds the tape's objects in this order."
  (let [out []]
    (var at 0)
    (each [_ o (ipairs plan.tape.objects)]
      (set at ((. (strategies.of o) :spheres) plan o at out)))
    out))

(fn plan-bounds [plan scene options]
  "{:count n} when every object of `plan` but the half-spaces has a bounding sphere
(`n` of them), else nil: then the marcher marches everything everywhere, as the
article's does. The scene's :render :bounds false, or `options.bounds?` false (the
benchmark's before), switch it off."
  (when (and (not= false options.bounds?) scene.render.bounds (not plan.uber?))
    (let [finite (finite-spheres plan)
          all? (accumulate [ok? true _ s (ipairs finite) &until (not ok?)] (not= false s))]
      (when all? {:count (length finite)}))))

(fn margin [radius centre-distance hit-threshold]
  ;; A ray that passes within the hit threshold of a surface counts as a hit: the
  ;; bound grows by twice the threshold where the object is, and by a thousandth of
  ;; its radius for float32 rounding in the GPU's test.
  (+ (* 2 (hit-threshold (+ centre-distance radius))) (* 0.001 radius)))

(fn spheres [plan cam-pos hit-threshold ?world?]
  "The bounding spheres of the finite objects of `plan`, camera-relative (in double;
in world coordinates with `?world?`) and grown by `margin`, as one flat list x y z r
per object."
  (let [[cx cy cz] (if ?world? [0 0 0] cam-pos)
        [kx ky kz] cam-pos
        out []]
    (each [_ [[x y z] r] (ipairs (finite-spheres plan))]
      (let [rel [(- x cx) (- y cy) (- z cz)]
            grown (+ r (margin r (length3 [(- x kx) (- y ky) (- z kz)]) hit-threshold))]
        (each [_ v (ipairs [(. rel 1) (. rel 2) (. rel 3) grown])] (table.insert out v))))
    out))

;; Texels to a line of the bounding spheres' image (a plan whose bounds have
;; :texture?: the interpreter's).
(local texture-width 1024)

(fn texture [flat]
  "The image of the bounding spheres in `flat` (spheres' list x y z r ...): texel 0
holds their count, texels 1 to n the spheres (shaders/pipeline/bounds.glsl's
spheres-texture), `texture-width` to a line."
  (let [n (/ (length flat) 4)
        data [n 0 0 0]
        texels (+ n 1)]
    (each [_ v (ipairs flat)] (table.insert data v))
    {:width (math.min texels texture-width) :height (math.ceil (/ texels texture-width))
     : data}))

(fn span [spheres ox oy oz dx dy dz far ?grow]
  "Where the ray o + t d (d a unit vector) is inside some bounding sphere of the flat
list `spheres`: enter and exit t, the union's first entry and last exit, or far and
0 when it meets none. With `?grow` g, each sphere of radius r whose centre is q from
o is grown by g (q + r): a soft shadow's penumbra, which widens with the distance
(see shadow-soft.glsl). The same arithmetic as boundsSpan in the shader."
  (var enter far)
  (var exit 0)
  (for [i 1 (length spheres) 4]
    ;; From the point of closest approach (no cancellation of large squares when a
    ;; far ray passes near a small sphere).
    (let [qx (- ox (. spheres i)) qy (- oy (. spheres (+ i 1))) qz (- oz (. spheres (+ i 2)))
          r0 (. spheres (+ i 3))
          r (+ r0 (* (or ?grow 0) (+ (math.sqrt (+ (* qx qx) (* qy qy) (* qz qz))) r0)))
          b (+ (* qx dx) (* qy dy) (* qz dz))
          ax (- qx (* b dx)) ay (- qy (* b dy)) az (- qz (* b dz))
          disc (- (* r r) (+ (* ax ax) (* ay ay) (* az az)))]
      (when (>= disc 0)
        (let [s (math.sqrt disc)
              t1 (+ (- b) s)]
          (when (> t1 0)
            (set enter (math.min enter (- (- b) s)))
            (set exit (math.max exit t1)))))))
  (values enter (math.min exit far)))

(fn others? [plan]
  "Whether `plan` marches finite objects of their own bounding spheres (beside a
field's members and the half-spaces): some counted, or any from an image (the
interpreter's bounds: their count is not in the code)."
  (and (not= nil plan.bounds) (or plan.bounds.texture? (> plan.bounds.count 0))))

{: plan-bounds : others? : spheres : span : object-sphere : grid-sphere : texture : texture-width}
