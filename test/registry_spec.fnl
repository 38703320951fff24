;; Specs for src/sdf/registry.fnl: kinds, parameters, CPU distance functions at known points
;; and the uniform packers (camera-relative values).
(local registry (require :src.sdf.registry))
(local primitives (require :src.sdf.primitives))

(fn near [expected actual ?tol]
  (let [tol (or ?tol 1e-12)]
    (assert (<= (math.abs (- expected actual)) tol)
            (.. "expected " expected " got " actual " (tolerance " tol ")"))))

(fn distance [kind o x y z]
  ((. (registry.lookup kind) :distance) o x y z))

(fn uniform [kind name]
  (accumulate [found nil _ u (ipairs (. (registry.lookup kind) :uniforms)) &until found]
    (when (= u.name name) u)))

(describe "registry: kinds"
  (fn []
    (it "lists sphere, box and plane in that order"
      (fn []
        (assert.are.same [:sphere :box :plane] (registry.kind-names))
        ;; The registry also holds :large-sphere, the lowering of big spheres, which
        ;; scene files cannot name.
        (assert.are.same [:sphere :large-sphere :box :plane]
                         (icollect [_ e (ipairs registry.kinds)] e.kind))
        (assert.is_true (. (registry.lookup :large-sphere) :internal?))))

    (it "looks kinds up by name and nothing else"
      (fn []
        (assert.are.equal :sphere (. (registry.lookup :sphere) :kind))
        (assert.are.equal :box (. (registry.lookup :box) :kind))
        (assert.are.equal :plane (. (registry.lookup :plane) :kind))
        (assert.is_nil (registry.lookup :torus))
        (assert.is_nil (registry.lookup :Sphere))))

    (it "declares parameters with types and defaults"
      (fn []
        (assert.are.same [{:name :pos :type :vec3 :default [0 0 0]}
                          {:name :radius :type :positive :default 1}
                          {:name :color :type :color :default [1 1 1]}]
                         (. (registry.lookup :sphere) :params))
        (assert.are.same [{:name :pos :type :vec3 :default [0 0 0]}
                          {:name :size :type :size3 :default [1 1 1]}
                          {:name :color :type :color :default [1 1 1]}]
                         (. (registry.lookup :box) :params))
        (assert.are.same [{:name :height :type :number :default 0}
                          {:name :color :type :color :default [1 1 1]}]
                         (. (registry.lookup :plane) :params))))

    (it "counts one uniform vector per uniform array element"
      (fn []
        (assert.are.equal 2 (registry.slots-per-object (registry.lookup :sphere)))
        (assert.are.equal 3 (registry.slots-per-object (registry.lookup :box)))
        (assert.are.equal 2 (registry.slots-per-object (registry.lookup :plane)))))

    (it "names uniforms and GLSL that exist in each kind's descriptor or chunk"
      (fn []
        (assert.are.same ["uSphere" "uSphereColor"]
                         (icollect [_ u (ipairs (. (registry.lookup :sphere) :uniforms))] u.name))
        (assert.are.same ["uBoxCenter" "uBoxHalfSize" "uBoxColor"]
                         (icollect [_ u (ipairs (. (registry.lookup :box) :uniforms))] u.name))
        (assert.are.same ["uPlaneHeight" "uPlaneColor"]
                         (icollect [_ u (ipairs (. (registry.lookup :plane) :uniforms))] u.name))
        (each [_ e (ipairs registry.kinds)]
          (let [text (if e.chunk
                         (with-open [f (assert (io.open e.chunk :rb))] (f:read :*a))
                         (. (primitives.lookup e.primitive) :glsl))
                fname (e.distance-glsl:match "^(%w+)%(")]
            (assert.truthy fname)
            (assert.truthy (text:find (.. "float " fname "(") 1 true))
            (assert.is_true e.exact?)
            ;; Every uniform the GLSL expressions use is one the kind declares.
            (each [name (: (.. e.distance-glsl " " e.color-glsl) :gmatch "(u%w+)%[i%]")]
              (assert.truthy (uniform e.kind name) name))
            ;; Every kind has its exact normal (the reference and normal-exact.glsl
            ;; count on it), calling a gradient its descriptor defines.
            (let [d (primitives.lookup (or e.gradient-of e.primitive))
                  gname (e.gradient-glsl:match "^(%w+)%(")]
              (assert.is_function e.gradient e.kind)
              (assert.truthy (d.gradient-glsl:find (.. "vec3 " gname "(") 1 true) e.kind)
              (each [name (e.gradient-glsl:gmatch "(u%w+)%[i%]")]
                (assert.truthy (uniform e.kind name) name)))))))))

(describe "registry: CPU distances"
  (fn []
    (it "sphere: -radius at the centre, 0 on the surface, exact outside"
      (fn []
        (let [o {:pos [1 2 3] :radius 2}]
          (assert.are.equal -2 (distance :sphere o 1 2 3))
          (assert.are.equal 0 (distance :sphere o 3 2 3))
          (assert.are.equal 0 (distance :sphere o 1 0 3))
          (assert.are.equal 0 (distance :sphere o 1 2 5))
          (assert.are.equal 3 (distance :sphere o 1 2 8))
          ;; 3-4-5 triangle: distance 5 from the centre.
          (assert.are.equal 3 (distance :sphere o 4 6 3))
          (assert.are.equal -1 (distance :sphere o 2 2 3)))))

    (it "box: negative inside, face distance, edge and corner distance"
      (fn []
        (let [o {:pos [0 0 0] :size [2 2 2]}]
          (assert.are.equal -1 (distance :box o 0 0 0))
          (assert.are.equal -0.5 (distance :box o 0.5 0 0))
          (assert.are.equal 0 (distance :box o 1 0 0))
          (assert.are.equal 2 (distance :box o 3 0 0))
          (assert.are.equal 2 (distance :box o 0 -3 0))
          (assert.are.equal 2 (distance :box o 0.5 0.5 3))
          (near (math.sqrt 2) (distance :box o 2 2 0))
          (near (math.sqrt 3) (distance :box o 2 2 2))
          (near (* 3 (math.sqrt 3)) (distance :box o 4 -4 4))
          (assert.are.equal 0 (distance :box o 1 1 1)))))

    (it "box: uses half the full size on each axis and the box's centre"
      (fn []
        (let [o {:pos [10 20 30] :size [2 4 6]}]
          ;; Inside: minus the nearest face distance (x half-size 1).
          (assert.are.equal -1 (distance :box o 10 20 30))
          (assert.are.equal 0 (distance :box o 10 22 30))
          (assert.are.equal 0 (distance :box o 10 20 33))
          (assert.are.equal 1 (distance :box o 10 20 34))
          (assert.are.equal 5 (distance :box o 16 20 30))
          ;; Seed box of size 5: corner at (2.5, 2.5, 2.5) from its centre.
          (let [seed-box {:pos [0 0 7.5] :size [5 5 5]}]
            (near (* 1 (math.sqrt 3)) (distance :box seed-box 3.5 3.5 11))
            (assert.are.equal -2.5 (distance :box seed-box 0 0 7.5))))))

    (it "plane: signed height above z = height, independent of x and y"
      (fn []
        (let [o {:height 2}]
          (assert.are.equal 3 (distance :plane o 0 0 5))
          (assert.are.equal 3 (distance :plane o 1e6 -1e6 5))
          (assert.are.equal 0 (distance :plane o 7 8 2))
          (assert.are.equal -2 (distance :plane o 0 0 0)))
        (assert.are.equal 20 (distance :plane {:height 0} 20 50 20))))

    (it "agrees with the box's faces from every side"
      (fn []
        (let [o {:pos [1 1 1] :size [2 2 2]}]
          (each [_ [x y z] (ipairs [[3 1 1] [-1 1 1] [1 3 1] [1 -1 1] [1 1 3] [1 1 -1]])]
            (assert.are.equal 1 (distance :box o x y z))))))))

(describe "registry: uniform packers"
  (fn []
    (it "sphere: camera-relative centre and the radius"
      (fn []
        (let [o {:pos [4 6 8] :radius 2 :color [0.1 0.2 0.3]}]
          (assert.are.same [3 4 5 2] ((. (uniform :sphere "uSphere") :pack) o [1 2 3]))
          (assert.are.same [4 6 8 2] ((. (uniform :sphere "uSphere") :pack) o [0 0 0]))
          (assert.are.same [0.1 0.2 0.3] ((. (uniform :sphere "uSphereColor") :pack) o [1 2 3]))
          (assert.are.equal :vec4 (. (uniform :sphere "uSphere") :type))
          (assert.are.equal :vec3 (. (uniform :sphere "uSphereColor") :type)))))

    (it "sphere: subtracts in double precision"
      (fn []
        (let [[x y z r] ((. (uniform :sphere "uSphere") :pack)
                         {:pos [100001 -2e6 0.5] :radius 3} [1e5 -2e6 0])]
          (assert.are.equal 1 x)
          (assert.are.equal 0 y)
          (assert.are.equal 0.5 z)
          (assert.are.equal 3 r))))

    (it "box: camera-relative centre, half sizes and colour"
      (fn []
        (let [o {:pos [-2.7 -2 2.5] :size [5 4 3] :color [0.79 0.69 0.59]}
              cam [20 50 20]]
          (assert.are.same [(- -2.7 20) -52 -17.5] ((. (uniform :box "uBoxCenter") :pack) o cam))
          (assert.are.same [2.5 2 1.5] ((. (uniform :box "uBoxHalfSize") :pack) o cam))
          (assert.are.same [0.79 0.69 0.59] ((. (uniform :box "uBoxColor") :pack) o cam)))))

    (it "plane: height relative to the camera's z only"
      (fn []
        (let [o {:height 0 :color [0.97 0.27 0.35]}]
          (assert.are.same [-20] ((. (uniform :plane "uPlaneHeight") :pack) o [20 50 20]))
          (assert.are.same [3] ((. (uniform :plane "uPlaneHeight") :pack) {:height 5} [100 100 2]))
          (assert.are.equal :float (. (uniform :plane "uPlaneHeight") :type))
          (assert.are.same [0.97 0.27 0.35] ((. (uniform :plane "uPlaneColor") :pack) o [0 0 0])))))

    (it "packs as many numbers as the uniform type holds"
      (fn []
        (let [sizes {:float 1 :vec3 3 :vec4 4}
              objects {:sphere {:pos [1 2 3] :radius 1 :color [1 1 1]}
                       :large-sphere {:pos [1 2 3] :radius 5000 :color [1 1 1]}
                       :box {:pos [1 2 3] :size [1 1 1] :color [1 1 1]}
                       :plane {:height 1 :color [1 1 1]}}]
          (each [_ e (ipairs registry.kinds)]
            (each [_ u (ipairs e.uniforms)]
              (assert.are.equal (. sizes u.type)
                                (length (u.pack (. objects e.kind) [5 6 7]))))))))))
