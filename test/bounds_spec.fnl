;; tier: fast
;; Bounds (src/render/bounds.fnl): bounding spheres of finite objects, which plans get
;; them, the ray's span inside them, and that the reference marcher gives the same
;; image with them as without (the GPU follows the same rules: gpu_vs_cpu_spec).

(local scene (require :src.scene.load))
(local plan (require :src.render.plan))
(local camera (require :src.render.camera))
(local reference (require :src.reference))
(local bounds (require :src.render.bounds))

(fn load [source] (assert (scene.load-string source "t.fnl")))

(fn near? [a b tol] (<= (math.abs (- a b)) tol))

(describe "bounds"
  (fn []
    (it "gives a sphere its own bound, a box its circumscribed sphere, a tree its child's box"
      (fn []
        (let [sphere-of (fn [source]
                          (let [s (load (.. "{:objects [" source "]}"))
                                p (assert (plan.scene->plan s))]
                            (bounds.object-sphere (. s.objects 1) (. p.tape.objects 1 :info))))]
          (assert.are.same [[1 2 3] 0.5] (sphere-of "{:kind :sphere :pos [1 2 3] :radius 0.5}"))
          ;; The same as a tree node.
          (assert.are.same [[1 2 3] 0.5] (sphere-of "{:kind :sphere :pos [1 2 3] :radius 0.5 :mirror 1}"))
          (let [[c r] (sphere-of "{:kind :box :pos [0 0 1] :size [2 2 2]}")]
            (assert.are.same [0 0 1] c)
            (assert.is_true (near? r (math.sqrt 3) 1e-12)))
          ;; A sphere of radius 1000 or more has none (float32 near its surface).
          (assert.is_nil (sphere-of "{:kind :sphere :pos [0 0 0] :radius 5000}")))
        (let [s (load "{:objects [{:kind :torus :radius 2 :thickness 0.5 :pos [5 0 1]}]}")
              p (assert (plan.scene->plan s))
              [[c r]] [(bounds.object-sphere (. s.objects 1) (. p.tape.objects 1 :info))]]
          (assert.are.same [5 0 1] c)
          ;; The torus's bounds are half extents 2.5 2.5 0.5.
          (assert.is_true (near? r (math.sqrt (+ 6.25 6.25 0.25)) 1e-9)))))

    (it "are planned only when every object but the half-spaces has one"
      (fn []
        (let [key (fn [file ?edit]
                    (let [s (assert (scene.load-file file))]
                      (when ?edit (?edit s))
                      (. (assert (plan.scene->plan s)) :bounds)))]
          (assert.are.same {:count 12} (key "scenes/gallery.fnl"))
          (assert.are.same {:count 3} (key "scenes/organic.fnl"))
          ;; The platonic shelf's wall is a plane with a normal of its own: a
          ;; half-space too.
          (assert.are.same {:count 3} (key "scenes/platonic-shelf.fnl"))
          ;; The seed keeps the article's march; colonnade repeats without end.
          (assert.is_nil (key "scenes/seed.fnl"))
          (assert.is_nil (key "scenes/colonnade.fnl"))
          (assert.is_nil (key "scenes/gallery.fnl" #(set $.render.bounds false)))
          (assert.is_nil (. (assert (plan.scene->plan (assert (scene.load-file "scenes/gallery.fnl"))
                                                      {:bounds? false}))
                            :bounds)))))

    (it "find where a ray is inside the spheres: first entry, last exit, or none"
      (fn []
        (let [spheres [0 0 10 1  0 0 20 2]]
          (let [(enter exit) (bounds.span spheres 0 0 0 0 0 1 1000)]
            (assert.is_true (near? enter 9 1e-12))
            (assert.is_true (near? exit 22 1e-12)))
          ;; Missed: (far, 0), so nothing is marched.
          (assert.are.same [1000 0] [(bounds.span spheres 0 0 0 1 0 0 1000)])
          ;; From inside the first: entry behind the origin.
          (let [(enter exit) (bounds.span spheres 0 0 10 0 0 1 1000)]
            (assert.is_true (< enter 0))
            (assert.is_true (near? exit 12 1e-12)))
          ;; Behind the ray: not met.
          (assert.are.same [1000 0] [(bounds.span spheres 0 0 30 0 0 1 1000)])
          ;; The exit is clipped to the draw distance.
          (assert.are.same 15 (select 2 (bounds.span spheres 0 0 0 0 0 1 15))))))

    (it "are sent camera-relative and grown by the hit threshold"
      (fn []
        (let [s (load "{:camera {:pos [0 -10 1]} :objects [{:kind :sphere :pos [3 0 1] :radius 1}]}")
              p (assert (plan.scene->plan s))
              [x y z r] (bounds.spheres p [0 -10 1] (fn [d] (* 1e-3 d)))]
          (assert.are.same [3 10 0] [x y z])
          ;; 1 + 2 * 1e-3 * (|(3 10 0)| + 1) + 0.001
          (assert.is_true (near? r (+ 1 (* 2e-3 (+ (math.sqrt 109) 1)) 0.001) 1e-12)))))

    (it "leave the reference's image as it was without them"
      (fn []
        ;; The same pixels of gallery and organic marched with and without bounds:
        ;; the same object under every pixel, colours within 2/255 but for grazing
        ;; pixels (a few per cent at most: steps start elsewhere, so edges flip).
        (each [_ file (ipairs ["scenes/gallery.fnl" "scenes/organic.fnl" "scenes/platonic-shelf.fnl"])]
          (let [s (assert (scene.load-file file))
                cam (camera.from-scene s)
                pixels (fcollect [i 0 299] [(% (* i 37) 96) (% (* i 11) 64)])
                with (reference.render-pixels s (assert (plan.scene->plan s)) cam 96 64 pixels)
                _ (set s.render.bounds false)
                without (reference.render-pixels s (assert (plan.scene->plan s)) cam 96 64 pixels)]
            (var same-object 0)
            (var close 0)
            (each [i a (ipairs with)]
              (let [b (. without i)]
                (when (= a.object b.object) (set same-object (+ same-object 1)))
                (when (accumulate [ok? true c x (ipairs a.color)]
                        (and ok? (<= (math.abs (- x (. b.color c))) (/ 2 255))))
                  (set close (+ close 1)))))
            (assert.is_true (>= same-object 297) (.. file ": same object at " same-object " of 300"))
            (assert.is_true (>= close 290) (.. file ": close colour at " close " of 300"))))))))
