;; The modern lighting model (issue 10) on the CPU, in double precision: the
;; reference for shaders/views/modern.glsl and shaders/shading/modern/, written from
;; the same description (the scene's :lighting section, lowered by plan.fnl and packed
;; by uniforms.fnl), never from the GLSL text. Uses a reference tracer's closures for
;; the distance field, its marches and its normals.

(local uniforms (require :src.render.uniforms))
(local feature-set (require :src.render.features))

(local sqrt math.sqrt)
(local exp math.exp)
(local max math.max)
(local min math.min)

(fn clamp01 [v]
  (if (< v 0) 0 (> v 1) 1 v))

(fn smoothstep [e0 e1 x]
  (let [t (clamp01 (/ (- x e0) (- e1 e0)))]
    (* t t (- 3 (* 2 t)))))

(fn safe-normalize [x y z]
  (let [len (sqrt (+ (* x x) (* y y) (* z z)))]
    (if (> len 0) (values (/ x len) (/ y len) (/ z len)) (values 0 0 1))))

(fn mix [a b w] (+ (* a (- 1 w)) (* b w)))

(fn shader [T scene plan]
  "A function (ox oy oz dx dy dz t) -> r g b: the modern model's display colour
(0..1) of the ray from (ox oy oz) along (dx dy dz) whose primary march gave `t`, for
`scene` lowered to `plan` (plan.lighting set), using tracer `T` (see
reference.tracer). Also returns the path: the plan index of each surface met, -1 for
the sky, and the surface points met ([x y z] each)."
  (let [L scene.lighting
        features plan.lighting
        draw scene.render.draw-distance
        reflections (if plan.reflections? plan.reflections 0)
        lights (icollect [_ l (ipairs L.lights)]
                 (let [[r g b] (uniforms.linear l.color l.intensity)]
                   {:sun? (= l.kind :sun) :dir l.direction :pos l.pos :range l.range
                    :softness l.softness : r : g : b}))
        [zr zg zb] (uniforms.linear L.sky-zenith)
        [hr hg hb] (uniforms.linear L.sky-horizon)
        sun (* (/ L.sun-size 180) math.pi)
        (edge0 edge1) (if (> sun 0) (values (math.cos sun) (math.cos (* 0.8 sun))) (values 2 3))
        shadows? plan.shadows?
        soft? features.soft?
        shadow-steps features.shadow-steps
        map T.map
        march T.march
        threshold T.threshold
        normal-delta T.normal-delta
        ;; The features' terms (src/render/features/), by the view's slot.
        terms (fn [slot]
                (icollect [_ name (ipairs features.features)]
                  (let [d (feature-set.lookup name)]
                    (when (= d.slot slot) (d.cpu L T)))))
        occlusion-terms (terms :occlusion)
        surface-terms (terms :surface)
        light-terms (terms :light)
        segment-terms (terms :segment)]

    (fn sky [dx dy dz]
      (let [w (sqrt (clamp01 dz))
            dark (- 1 (* 0.5 (clamp01 (* -4 dz))))]
        (var (r g b) (values (* (mix hr zr w) dark) (* (mix hg zg w) dark) (* (mix hb zb w) dark)))
        (each [_ l (ipairs lights)]
          (when l.sun?
            (let [[lx ly lz] l.dir
                  disc (* 8 (smoothstep edge0 edge1 (+ (* dx lx) (* dy ly) (* dz lz))))]
              (set (r g b) (values (+ r (* l.r disc)) (+ g (* l.g disc)) (+ b (* l.b disc)))))))
        (values r g b)))

    (fn hard-visibility [ox oy oz lx ly lz reach]
      (let [ts (march ox oy oz lx ly lz reach)]
        (if (< ts reach) 0 1)))

    (fn soft-visibility [ox oy oz lx ly lz reach softness]
      ;; Quilez's improved penumbra estimate, as shadow-soft.glsl; with bounds only
      ;; over the span of the bounding spheres grown by the penumbra (codegen's
      ;; soft-span-lines), the planes met in closed form.
      (let [t0 (T.distance-from-camera ox oy oz)
            f (if T.soft-span T.map-finite map)]
        (var seen 1)
        (var t 0)
        (var h-prev 1e10)
        ;; As the marches: a hit must come nearer than start-limit of the start's
        ;; distance.
        (var start-half 1e10)
        (var first? true)
        (var result nil)
        (var limit reach)
        (when T.soft-span
          (if (< (T.planes-hit ox oy oz lx ly lz) reach)
              (set result 0)
              (let [(enter exit) (if (< softness 0.5)
                                     (T.soft-span ox oy oz lx ly lz (/ softness (- 1 softness)))
                                     (values 0 draw))]
                (set t (max enter 0))
                (set limit (min reach exit))
                (when (>= t limit) (set result -1)))))
        (for [_ 1 shadow-steps &until result]
          (let [h (f (+ ox (* lx t)) (+ oy (* ly t)) (+ oz (* lz t)))]
            (when (and first? (= t 0)) (set start-half (T.start-limit h)))
            (set first? false)
            (if (< h (min (threshold (+ t0 t)) start-half))
                (set result 0)
                (let [y (/ (* h h) (* 2 h-prev))
                      closest (sqrt (max (- (* h h) (* y y)) 0))]
                  ;; At or behind the origin the closest approach is the surface
                  ;; the ray leaves (shadow-soft.glsl): no darkening.
                  (let [along (- t y)]
                    (when (> along 0)
                      (set seen (min seen (/ closest (* softness along))))))
                  (set h-prev h)
                  (set t (+ t h))
                  (when (>= t limit) (set result -1))))))
        (if (= result 0) 0
            (let [s (clamp01 seen)] (* s s (- 3 (* 2 s)))))))

    (fn visibility [ox oy oz lx ly lz reach softness]
      (if (not shadows?) 1
          (and soft? (> softness 0)) (soft-visibility ox oy oz lx ly lz reach softness)
          (hard-visibility ox oy oz lx ly lz reach)))

    (fn direct-light [px py pz nx ny nz vx vy vz ar ag ab mirror roughness]
      (var (r g b) (values 0 0 0))
      (local surface {:n [nx ny nz] :v [vx vy vz] :albedo [ar ag ab] : mirror : roughness})
      (let [s (* 2 (normal-delta px py pz))
            ox (+ px (* nx s)) oy (+ py (* ny s)) oz (+ pz (* nz s))]
        (each [_ l (ipairs lights)]
          (let [(lx ly lz falloff reach)
                (if l.sun?
                    (let [[x y z] l.dir] (values x y z 1 draw))
                    (let [[qx qy qz] l.pos
                          tx (- qx px) ty (- qy py) tz (- qz pz)
                          dist (sqrt (+ (* tx tx) (* ty ty) (* tz tz)))
                          q (/ dist l.range)]
                      (values (if (> dist 0) (/ tx dist) nx) (if (> dist 0) (/ ty dist) ny)
                              (if (> dist 0) (/ tz dist) nz)
                              (/ 1 (+ 1 (* q q)))
                              (min (- dist (* 2 (normal-delta qx qy qz))) draw))))
                lambert (+ (* nx lx) (* ny ly) (* nz lz))]
            (when (> lambert 0)
              (let [visible (visibility ox oy oz lx ly lz reach l.softness)
                    k (* falloff lambert visible)
                    lr (* l.r k) lg (* l.g k) lb (* l.b k)]
                (set (r g b) (values (+ r (* ar lr)) (+ g (* ag lg)) (+ b (* ab lb))))
                ;; The features' terms per light (specular).
                (each [_ f (ipairs light-terms)]
                  (let [(dr dg db) (f surface lx ly lz lr lg lb)]
                    (set (r g b) (values (+ r dr) (+ g dg) (+ b db))))))))))
      (values r g b))

    (fn [ox oy oz dx dy dz t-primary]
      (var (rr rg rb) (values 0 0 0))      ; radiance
      (var (wr wg wb) (values 1 1 1))      ; path weight
      (var (qx qy qz) (values ox oy oz))   ; segment origin
      (var (vx vy vz) (values dx dy dz))   ; segment direction
      (var t t-primary)
      (var done? false)
      (local path [])
      (local points [])
      (for [bounce 0 reflections &until done?]
        (when (> bounce 0) (set t (march qx qy qz vx vy vz)))
        (if (>= t draw)
            (let [(sr sg sb) (sky vx vy vz)]
              (set (rr rg rb) (values (+ rr (* wr sr)) (+ rg (* wg sg)) (+ rb (* wb sb))))
              (table.insert path -1)
              (set done? true))
            (let [px (+ qx (* vx t)) py (+ qy (* vy t)) pz (+ qz (* vz t))
                  (nx ny nz) (T.normal px py pz)
                  (_ i cr cg cb mirror roughness emission) (T.map-color px py pz)
                  ar (math.pow cr 2.2) ag (math.pow cg 2.2) ab (math.pow cb 2.2)
                  cos-view (clamp01 (- (+ (* nx vx) (* ny vy) (* nz vz))))
                  f0 (mix 0.04 1 mirror)
                  smooth (- 1 roughness)
                  reflected (* (+ f0 (* (- 1 f0) (math.pow (- 1 cos-view) 5))) smooth smooth)
                  occ (accumulate [occ 1 _ f (ipairs occlusion-terms)]
                        (* occ (f px py pz nx ny nz)))
                  sky-w (+ 0.5 (* 0.5 nz))
                  amb (* L.ambient occ)
                  (lr lg lb) (direct-light px py pz nx ny nz (- vx) (- vy) (- vz) ar ag ab
                                           mirror roughness)
                  keep (- 1 reflected)
                  sky-r (mix hr zr sky-w) sky-g (mix hg zg sky-w) sky-b (mix hb zb sky-w)
                  surface {:p [px py pz] :n [nx ny nz] :v [(- vx) (- vy) (- vz)]
                           :albedo [ar ag ab] : cos-view :sky [sky-r sky-g sky-b]
                           : mirror : roughness}
                  (sr sg sb) (accumulate [(r g b) (values (+ (* keep (+ lr (* ar sky-r amb))) (* ar emission))
                                                          (+ (* keep (+ lg (* ag sky-g amb))) (* ag emission))
                                                          (+ (* keep (+ lb (* ab sky-b amb))) (* ab emission)))
                                          _ f (ipairs surface-terms)]
                               (let [(dr dg db) (f surface)] (values (+ r dr) (+ g dg) (+ b db))))]
              (table.insert path (or i 0))
              (table.insert points [px py pz])
              ;; The features' terms on the segment (fog): what crosses it, and what
              ;; they add, times the path's weight so far.
              (var through 1)
              (each [_ f (ipairs segment-terms)]
                (let [(k gr gg gb) (f qx qy qz vx vy vz t)]
                  (set through (* through k))
                  (set (rr rg rb) (values (+ rr (* wr gr)) (+ rg (* wg gg)) (+ rb (* wb gb))))))
              (set (wr wg wb) (values (* wr through) (* wg through) (* wb through)))
              (set (rr rg rb) (values (+ rr (* wr sr)) (+ rg (* wg sg)) (+ rb (* wb sb))))
              (set (wr wg wb) (values (* wr reflected (mix 1 ar mirror))
                                      (* wg reflected (mix 1 ag mirror))
                                      (* wb reflected (mix 1 ab mirror))))
              (if (< (max wr wg wb) 0.002)
                  (set done? true)
                  (let [s (* 2 (normal-delta px py pz))
                        k (* 2 (+ (* vx nx) (* vy ny) (* vz nz)))]
                    (set (qx qy qz) (values (+ px (* nx s)) (+ py (* ny s)) (+ pz (* nz s))))
                    (set (vx vy vz) (values (- vx (* k nx)) (- vy (* k ny)) (- vz (* k nz)))))))))
      (let [e L.exposure
            display (fn [c] (math.pow (- 1 (exp (- (* c e)))) (/ 1 2.2)))]
        (values (display rr) (display rg) (display rb) path points)))))

{: shader}
