;; The CPU reference marcher: the shader's semantics in plain LuaJIT, double precision,
;; written independently of the GLSL. Its distances come from the same descriptions as
;; the shader's (the tape's CPU evaluator, src/sdf/emit-lua.fnl, and a field's grid),
;; so a GPU image can be checked pixel by pixel. Its parts live in src/reference/:
;; settings (what it reads from the scene and plan), distance (the distance field),
;; hit (hit tests), march and field-walk, normals, shading (the classic model and the
;; debug views), lighting and shadows (the modern model), rays (camera rays and the
;; edge tests) and vec.
;;
;; Vectors travel as multiple values (x y z) and the inner loops allocate nothing.

;; `pairs` under another name: a loop over `pairs` by that name is LuaJIT's ITERN,
;; which Debian 12's LuaJIT ends early once despecialised (see src/util/wire.fnl).
(local each-pair pairs)

(local camera (require :src.render.camera))
(local bounds (require :src.render.bounds))
(local settings (require :src.reference.settings))
(local distance (require :src.reference.distance))
(local hit (require :src.reference.hit))
(local march (require :src.reference.march))
(local normals (require :src.reference.normals))
(local shading (require :src.reference.shading))
(local lighting (require :src.reference.lighting))
(local rays (require :src.reference.rays))

(local public-closures
  [:map :map-color :march :normal :lightness :trace :normal-delta :crease?
   :needs-samples? :map-finite :map-estimate :map-finite-estimate :planes-hit :soft-span
   :threshold :start-limit :distance-from-camera])

(fn merge [into from]
  (each [k v (each-pair from)] (tset into k v))
  into)

(fn tracer [scene plan ?options]
  "A tracer for `scene` lowered to `plan`. Options: :cam-pos (the camera position,
which scaled hit tests measure distances from; default the origin), :pixel-angle
(1 / (projection distance * image height), for the :pixel hit test) and :counts (a
table the shaded view adds its distance evaluations to, as the shader makes them:
:primary, :shadow and :mirror march steps, :normal (differences; none for exact
normals) and :color (mapColor calls, one per hit)).
Returns a table of closures
  :map        (fn [x y z]) -> distance (never above the draw distance)
  :map-color  (fn [x y z]) -> distance, index into plan.objects or nil
  :march      (fn [ox oy oz dx dy dz]) -> t, steps
  :normal     (fn [x y z]) -> nx ny nz (plan.normals differences of the nearest
               object's distance, or with :normals-of :scene the whole scene's)
  :lightness  (fn [px py pz nx ny nz]) -> lambert, shadowed?
  :trace      (fn [ox oy oz dx dy dz]) -> {:color [r g b] :hit? :distance :steps
               :object (scene index or nil) :shadowed? :lightness :path :points}
               (shaded view: :points, the surface points along the path)
  :crease?    (fn [x y z]) -> whether two objects come within twice normal-delta
  :needs-samples? (fn [ox oy oz dx dy dz t]) -> whether adaptive supersampling's
               edge tests want the pixel's grid of rays after a centre ray that went t
Also :map-finite, :planes-hit, :soft-span (soft shadows' span of the bounding
spheres, or nil), :threshold, :start-limit, :distance-from-camera and :normal-delta
(see src/reference/distance.fnl and hit.fnl).
Positions are in world coordinates."
  (let [ctx (settings.settings scene plan ?options)
        parts (merge (distance.evaluators ctx) (hit.tests ctx))
        draw ctx.draw]
    ;; With bounds (src/render/bounds.fnl), as the shader: the half-spaces met in
    ;; closed form, the other objects marched over the span of their bounding spheres.
    (set parts.bound-spheres (when plan.bounds
                               (bounds.spheres plan ctx.cam parts.threshold true)))
    ;; Soft shadows over the span of the bounding spheres grown by `grow` (see
    ;; plan.lighting.soft-bounded? in src/render/plan.fnl).
    (set parts.soft-span (when (?. plan :lighting :soft-bounded?)
                           (fn [ox oy oz dx dy dz grow]
                             (bounds.span parts.bound-spheres ox oy oz dx dy dz draw grow))))
    ;; Whether the field read as an estimate differs from the steps' (see
    ;; :estimates? in src/sdf/lower.fnl): the soft shadows read it twice then.
    (set parts.estimates? (= true (?. plan :tape :estimates?)))
    (set parts.march (march.marcher ctx parts))
    (merge parts (normals.normals ctx parts))
    (set parts.lightness (shading.lighter ctx parts))
    (set parts.needs-samples? (rays.edge-test ctx parts))
    (when (and ctx.shaded? plan.lighting)
      (set parts.modern-shade (lighting.shader parts scene plan)))
    (set parts.trace (shading.tracer ctx parts))
    (collect [_ k (ipairs public-closures)] k (. parts k))))

(fn render-pixels [scene plan cam width height pixels ?counts]
  "Reference colours of `pixels` (a list of [x y], 0-based from the top-left) of a
width x height image of `scene` lowered to `plan` seen by camera state `cam`.
Returns a list of {:x :y :color [r g b] (0..1, clamped) :hit? :distance t :steps n
:object (scene index of the object hit, or nil) :shadowed? :lightness :path}, in the
order of `pixels`. :path lists the scene index of the object hit by the primary ray
and each bounce (-1: the bounce escaped). With supersampling (plan.samples N > 1) the
colour is the mean of N x N rays on a grid inside the pixel, each clamped, as the
shader's; the other fields are the first ray's. Adaptive (plan.adaptive?): the centre
ray's result with the colour the mean of it and a second ray's (plan.edge-tests),
unless the centre ray finds an edge or the two differ (then :edge? is true and the
colour is the grid's mean). `?counts` gathers the distance evaluations (see tracer)."
  (let [T (tracer scene plan {:cam-pos cam.pos :counts ?counts
                             :pixel-angle (/ 1 (* (camera.projection-distance cam) height))})
        ray (rays.ray-setup cam width height)
        [ox oy oz] cam.pos
        n (or plan.samples 1)]
    (icollect [_ [x y] (ipairs pixels)]
      (let [centre (when (or (= n 1) plan.adaptive?) (T.trace ox oy oz (ray x y)))
            tests plan.edge-tests
            geometric? (and plan.adaptive?
                            (let [(dx dy dz) (ray x y)]
                              (T.needs-samples? ox oy oz dx dy dz centre.distance)))
            ;; No edge on the centre ray: a second ray, and the grid only when its
            ;; colour's luma differs by more than tests.contrast (adaptive.glsl).
            second (when (and plan.adaptive? (not geometric?))
                     (T.trace ox oy oz (ray x y (. tests.second 1) (. tests.second 2))))
            contrast? (when second
                        (let [[r1 g1 b1] centre.color [r2 g2 b2] second.color]
                          (> (math.abs (+ (* 0.2126 (- r2 r1)) (* 0.7152 (- g2 g1)) (* 0.0722 (- b2 b1))))
                             tests.contrast)))
            edge? (or geometric? contrast?)
            result (if (= n 1) centre
                       (and plan.adaptive? (not edge?))
                       (doto centre
                         (tset :color (icollect [i c (ipairs centre.color)]
                                        (* 0.5 (+ c (. second.color i))))))
                       (let [sum [0 0 0]]
                         (var first nil)
                         (for [j 0 (- n 1)]
                           (for [i 0 (- n 1)]
                             (let [r (T.trace ox oy oz (ray x y (/ (+ i 0.5) n) (/ (+ j 0.5) n)))]
                               (when (not first) (set first r))
                               (for [c 1 3] (tset sum c (+ (. sum c) (. r.color c)))))))
                         (set first.color (icollect [_ v (ipairs sum)] (/ v (* n n))))
                         first))]
        (set result.x x)
        (set result.y y)
        (when plan.adaptive? (set result.edge? edge?))
        result))))

{: tracer :ray-setup rays.ray-setup : render-pixels :heat-color shading.heat-color}
