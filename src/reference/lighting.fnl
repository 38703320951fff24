;; The modern lighting model (sky, sun and point lights, materials) on the CPU, in
;; double precision: the reference for shaders/views/modern.glsl and
;; shaders/shading/modern/, written from the same description (the scene's :lighting
;; section, lowered by plan.fnl and packed by uniforms.fnl), never from the GLSL text.
;; Uses a reference tracer's parts for the distance field, its marches and its
;; normals; shadows in src/reference/shadows.fnl.

(local uniforms (require :src.render.uniforms))
(local feature-set (require :src.render.features))
(local shadows (require :src.reference.shadows))
(local {: clamp01 : smoothstep : mix} (require :src.reference.vec))

(local sqrt math.sqrt)
(local exp math.exp)
(local max math.max)
(local min math.min)

(fn light-list [L]
  "The scene's lights in linear colour: {:sun? :dir :pos :range :softness :r :g :b}."
  (icollect [_ l (ipairs L.lights)]
    (let [[r g b] (uniforms.linear l.color l.intensity)]
      {:sun? (= l.kind :sun) :dir l.direction :pos l.pos :range l.range
       :softness l.softness : r : g : b})))

(fn sky-fn [L lights]
  (let [[zr zg zb] (uniforms.linear L.sky-zenith)
        [hr hg hb] (uniforms.linear L.sky-horizon)
        sun (* (/ L.sun-size 180) math.pi)
        (edge0 edge1) (if (> sun 0) (values (math.cos sun) (math.cos (* 0.8 sun))) (values 2 3))]
    (fn [dx dy dz]
      (let [w (sqrt (clamp01 dz))
            dark (- 1 (* 0.5 (clamp01 (* -4 dz))))]
        (var (r g b) (values (* (mix hr zr w) dark) (* (mix hg zg w) dark) (* (mix hb zb w) dark)))
        (each [_ l (ipairs lights)]
          (when l.sun?
            (let [[lx ly lz] l.dir
                  disc (* 8 (smoothstep edge0 edge1 (+ (* dx lx) (* dy ly) (* dz lz))))]
              (set (r g b) (values (+ r (* l.r disc)) (+ g (* l.g disc)) (+ b (* l.b disc)))))))
        (values r g b)))))

(fn direct-light-fn [T lights visibility light-terms draw]
  (let [normal-delta T.normal-delta]
    (fn [px py pz nx ny nz vx vy vz ar ag ab mirror roughness]
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
      (values r g b))))

(fn shader [T scene plan]
  "A function (ox oy oz dx dy dz t) -> r g b: the modern model's display colour
(0..1) of the ray from (ox oy oz) along (dx dy dz) whose primary march gave `t`, for
`scene` lowered to `plan` (plan.lighting set), using tracer parts `T` (see
src/reference.fnl). Also returns the path: the plan index of each surface met, -1 for
the sky, and the surface points met ([x y z] each)."
  (let [L scene.lighting
        features plan.lighting
        draw scene.render.draw-distance
        reflections (if plan.reflections? plan.reflections 0)
        lights (light-list L)
        [zr zg zb] (uniforms.linear L.sky-zenith)
        [hr hg hb] (uniforms.linear L.sky-horizon)
        sky (sky-fn L lights)
        march T.march
        normal-delta T.normal-delta
        ;; The features' terms (src/render/features/), by the view's slot.
        terms (fn [slot]
                (icollect [_ name (ipairs features.features)]
                  (let [d (feature-set.lookup name)]
                    (when (= d.slot slot) (d.cpu L T)))))
        occlusion-terms (terms :occlusion)
        surface-terms (terms :surface)
        light-terms (terms :light)
        segment-terms (terms :segment)
        direct-light (direct-light-fn T lights (shadows.visibility T plan draw) light-terms draw)]
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

{: shader : light-list}
