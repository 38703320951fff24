;; tier: fast
;; Distance functions as a Shadertoy author writes them (issue 44): vectors [a b c],
;; arrays indexed by a loop counter, &until and a stop of (math.min n K) in the
;; translator (src/sdf/translate.fnl). Each well-known distance, written the natural
;; way, is checked against a plain scalar implementation written here, not by the
;; translator; its texts pass the main process's checks and its GLSL validates; every
;; refusal names its line and what to write; the example scenes of examples/ load,
;; and one renders on the GPU as the CPU reference draws it.
(local fennel (require :fennel))
(local translate (require :src.sdf.translate))
(local custom (require :src.sdf.custom))
(local load (require :src.scene.load))
(local glslang (. (require :test.support.glslang) :ok?))
(local {: lcg} (require :test.support.fields))

(fn parse [source]
  (let [(_ form) ((fennel.parser (fennel.string-stream source) "t.fnl"))] form))

;; GLSL's functions Lua's math lacks: a name taken from math holds nil in the file.
(local glsl-only {:clamp true :mix true :fract true :sign true :step true :smoothstep true
                  :round true :mod true :dot true :cross true :normalize true})

(fn resolver [tables]
  "A resolver as the loader's, for names from outside the function: math's functions,
GLSL's (nil in the file), and the file's arrays `tables`."
  (fn [name]
    (if (. tables name) {:table (. tables name)}
        (. glsl-only name) {:nil true}
        (= (type (. math name)) :function) {:math name})))

(fn translated [source ?tables]
  (assert (translate.translate (parse source) {:resolve (resolver (or ?tables {}))})))

;;; The reference: plain scalar math, written out here.

(fn clamp [x lo hi] (math.min (math.max x lo) hi))
(fn len2 [x y] (math.sqrt (+ (* x x) (* y y))))
(fn len3 [x y z] (math.sqrt (+ (* x x) (* y y) (* z z))))
(fn fmod [x y] (- x (* y (math.floor (/ x y)))))

(fn ref-box [x y z bx by bz]
  (let [qx (- (math.abs x) bx) qy (- (math.abs y) by) qz (- (math.abs z) bz)]
    (+ (len3 (math.max qx 0) (math.max qy 0) (math.max qz 0))
       (math.min (math.max qx qy qz) 0))))

(fn ref-capsule [x y z]
  ;; From a = (-0.5 0.2 0.1) to b = (0.6 -0.3 0.4), radius 0.3.
  (let [[ax ay az] [-0.5 0.2 0.1]
        [bx by bz] [0.6 -0.3 0.4]
        pax (- x ax) pay (- y ay) paz (- z az)
        bax (- bx ax) bay (- by ay) baz (- bz az)
        h (clamp (/ (+ (* pax bax) (* pay bay) (* paz baz)) (+ (* bax bax) (* bay bay) (* baz baz))) 0 1)]
    (- (len3 (- x (+ ax (* h bax))) (- y (+ ay (* h bay))) (- z (+ az (* h baz)))) 0.3)))

;; A non-convex polygon, counter-clockwise.
(local polygon [[0.9 -0.6] [0.2 0.1] [0.8 0.7] [-0.5 0.8] [-0.9 -0.4] [-0.1 -0.2]])

(fn ref-polygon [verts px py]
  ;; IQ's sdPolygon: the nearest edge; the sign by the winding of crossings.
  (let [n (length verts)]
    (var d math.huge)
    (var s 1)
    (for [i 1 n]
      (let [[vix viy] (. verts i)
            [vjx vjy] (. verts (if (= i 1) n (- i 1)))
            ex (- vjx vix) ey (- vjy viy)
            wx (- px vix) wy (- py viy)
            t (clamp (/ (+ (* wx ex) (* wy ey)) (+ (* ex ex) (* ey ey))) 0 1)
            bx (- wx (* ex t)) by (- wy (* ey t))
            c1 (>= py viy) c2 (< py vjy) c3 (> (* ex wy) (* ey wx))]
        (set d (math.min d (+ (* bx bx) (* by by))))
        (when (or (and c1 c2 c3) (and (not c1) (not c2) (not c3)))
          (set s (- s)))))
    (* s (math.sqrt d))))

(fn ref-prism [verts x y z height]
  (let [dx (ref-polygon verts x y) dz (- (math.abs z) height)]
    (+ (math.min (math.max dx dz) 0) (len2 (math.max dx 0) (math.max dz 0)))))

(fn ref-round-cone [x y z r1 r2 h]
  (let [qx (len2 x y) qy z
        b (/ (- r1 r2) h)
        a (math.sqrt (- 1 (* b b)))
        k (+ (* qx (- b)) (* qy a))]
    (if (< k 0) (- (len2 qx qy) r1)
        (> k (* a h)) (- (len2 qx (- qy h)) r2)
        (- (+ (* qx a) (* qy b)) r1))))

(fn ref-ellipsoid [x y z]
  ;; IQ's bound of an ellipsoid of radii (0.8 0.5 0.3).
  (let [rx 0.8 ry 0.5 rz 0.3
        k0 (len3 (/ x rx) (/ y ry) (/ z rz))
        k1 (len3 (/ x (* rx rx)) (/ y (* ry ry)) (/ z (* rz rz)))]
    (/ (* k0 (- k0 1)) k1)))

(fn ref-menger [x y z levels]
  (var d (ref-box x y z 1 1 1))
  (var s 1)
  (for [m 1 (math.min levels 4)]
    (let [ax (- (fmod (* x s) 2) 1) ay (- (fmod (* y s) 2) 1) az (- (fmod (* z s) 2) 1)
          s3 (* s 3)
          rx (math.abs (- 1 (* 3 (math.abs ax))))
          ry (math.abs (- 1 (* 3 (math.abs ay))))
          rz (math.abs (- 1 (* 3 (math.abs az))))
          da (math.max rx ry) db (math.max ry rz) dc (math.max rz rx)]
      (set s s3)
      (set d (math.max d (/ (- (math.min da db dc) 1) s)))))
  d)

(fn ref-repeat [x y z]
  ;; Spheres of radius 0.2 repeated every 2 units, shifted each turn, until one is
  ;; near: &until.
  (var d 1e30)
  (var k 0)
  (var i 1)
  (while (and (<= i 8) (not (< d 0.05)))
    (let [fract #(- $ (math.floor $))
          qx (- (fract (* (+ x (* i 0.37)) 0.5)) 0.5)
          qy (- (fract (* (+ y (* i 0.37)) 0.5)) 0.5)
          qz (- (fract (* (+ z (* i 0.37)) 0.5)) 0.5)]
      (set d (math.min d (- (len3 qx qy qz) 0.2)))
      (set k (+ k 1)))
    (set i (+ i 1)))
  (+ d (* 0.001 k)))

(local weights [0.5 -0.25 0.125 2 -1])

(fn ref-misc [x y z n]
  ;; Rotations of (x y) by a helper, a vector var, cross, normalize, floor, sign, step
  ;; and an array of numbers indexed by the counter (the source below).
  (var qx x) (var qy y) (var qz z)
  (var w 0)
  (for [i 1 (math.min n 5)]
    (let [c 0.8 s 0.6
          rx (- (* c qx) (* s qy)) ry (+ (* s qx) (* c qy))]
      (set qx (+ rx 0.1)) (set qy ry) (set qz (- qz))
      (set w (+ w (* (. weights i) (. weights (+ 1 (% i 5))))))))
  (let [;; cross (q, (0.3 0.4 0.5))
        cx (- (* qy 0.5) (* qz 0.4)) cy (- (* qz 0.3) (* qx 0.5)) cz (- (* qx 0.4) (* qy 0.3))
        ;; (set acc [(. acc 2) (. acc 1) (. acc 3)])
        ax cy ay cx az cz
        nx (+ qx 1) ny (+ qy 2) nz (+ qz 3)
        nl (len3 nx ny nz)
        sign #(if (> $ 0) 1 (< $ 0) -1 0)]
    (+ (/ nx nl) (+ (* ax 0.1) (* ay 0.2) (* az 0.3)) (math.floor qy) (sign qz)
       (if (< qx 0) 0 1) (len2 x y) (* 0.01 w))))

;;; The distances, written with vectors.

(local shapes
  [{:name "IQ's box (x y z and params)"
    :source "(fn [x y z bx by bz]
  (let [p [x y z]
        b [bx by bz]
        q (- (abs p) b)]
    (+ (length (max q 0)) (min (max (. q 1) (max (. q 2) (. q 3))) 0))))"
    :params [0.7 0.4 0.55] :reference ref-box}
   {:name "a capsule from dot, clamp and mix (the point as one vector)"
    :source "(fn [p]
  (let [a [-0.5 0.2 0.1] b [0.6 -0.3 0.4] r 0.3
        pa (- p a) ba (- b a)
        h (clamp (/ (dot pa ba) (dot ba ba)) 0 1)]
    (- (length (- p (mix a b h))) r)))"
    :params [] :reference ref-capsule}
   {:name "an extruded sdPolygon: a constant array of the file, a loop, a helper of a vector"
    :tables {:polygon polygon}
    :source "(fn [x y z height]
  (fn sd-polygon [p]
    (var d math.huge)
    (var s 1)
    (for [i 1 6]
      (let [j (if (= i 1) 6 (- i 1))
            vi (. polygon i)
            vj (. polygon j)
            e (- vj vi)
            w (- p vi)
            b (- w (* e (clamp (/ (dot w e) (dot e e)) 0 1)))
            [_ py] p
            c1 (>= py (. vi 2))
            c2 (< py (. vj 2))
            c3 (> (* (. e 1) (. w 2)) (* (. e 2) (. w 1)))]
        (set d (min d (dot b b)))
        (when (or (and c1 c2 c3) (and (not c1) (not c2) (not c3)))
          (set s (- s)))))
    (* s (sqrt d)))
  (let [w [(sd-polygon [x y]) (- (abs z) height)]]
    (+ (min (max (. w 1) (. w 2)) 0) (length (max w 0)))))"
    :params [0.3] :reference (partial ref-prism polygon)}
   {:name "IQ's rounded cone (destructured point, if with early values)"
    :source "(fn [x y z r1 r2 h]
  (let [q [(length [x y]) z]
        b (/ (- r1 r2) h)
        a (sqrt (- 1 (* b b)))
        k (dot q [(- b) a])]
    (if (< k 0) (- (length q) r1)
        (> k (* a h)) (- (length (- q [0 h])) r2)
        (- (dot q [a b]) r1))))"
    :params [0.45 0.2 0.9] :reference ref-round-cone}
   {:name "IQ's ellipsoid (radii an array of the file)"
    :tables {:radii [0.8 0.5 0.3]}
    :source "(fn [p]
  (let [k0 (length (/ p radii))
        k1 (length (/ p (* radii radii)))]
    (/ (* k0 (- k0 1)) k1)))"
    :params [] :reference ref-ellipsoid}
   {:name "a Menger fold with mod, levels a parameter of at most 4"
    :source "(fn [x y z levels]
  (fn sd-box [p b]
    (let [q (- (abs p) b)]
      (+ (length (max q 0)) (min (max (. q 1) (max (. q 2) (. q 3))) 0))))
  (let [p [x y z]]
    (var d (sd-box p [1 1 1]))
    (var s 1)
    (for [m 1 (math.min levels 4)]
      (let [a (- (mod (* p s) 2) 1)
            s3 (* s 3)
            r (abs (- 1 (* 3 (abs a))))
            da (max (. r 1) (. r 2))
            db (max (. r 2) (. r 3))
            dc (max (. r 3) (. r 1))]
        (set s s3)
        (set d (max d (/ (- (min da db dc) 1) s)))))
    d))"
    :params [3] :params-tried [[0] [1] [2] [3] [4] [6]] :reference ref-menger}
   {:name "repetition with fract, ended by &until"
    :source "(fn [p]
  (var d math.huge)
  (var k 0)
  (for [i 1 8 &until (< d 0.05)]
    (let [q (- (fract (* (+ p (* i 0.37)) 0.5)) 0.5)]
      (set d (min d (- (length q) 0.2)))
      (set k (+ k 1))))
  (+ d (* 0.001 k)))"
    :params [] :reference ref-repeat}
   {:name "helpers of vectors, a vector var, cross, normalize, floor, sign, step, an array of numbers"
    :tables {:weights weights}
    :source "(fn [x y z n]
  (fn rot [[a b] c s] [(- (* c a) (* s b)) (+ (* s a) (* c b))])
  (var q [x y z])
  (var w 0)
  (for [i 1 (math.min n 5)]
    (let [[qx qy qz] q
          [rx ry] (rot [qx qy] 0.8 0.6)]
      (set q [(+ rx 0.1) ry (- qz)])
      (set w (+ w (* (. weights i) (. weights (+ 1 (% i 5))))))))
  (var acc [0 0 0])
  (set acc (+ acc (cross q [0.3 0.4 0.5])))
  (set acc [(. acc 2) (. acc 1) (. acc 3)])
  (+ (. (normalize (+ q [1 2 3])) 1) (dot acc [0.1 0.2 0.3]) (. (floor q) 2) (. (sign q) 3)
     (. (step 0 q) 1) (length [x y]) (* 0.01 w)))"
    :params [3] :params-tried [[0] [1] [3] [5] [7]] :reference ref-misc}])

(describe "vectors in distance functions"
  (fn []
    (each [_ shape (ipairs shapes)]
      (it (.. shape.name ": the Lua gives what a scalar implementation gives, at 200 points")
        (fn []
          (let [t (translated shape.source shape.tables)
                f (translate.compile-lua t.lua)
                unpack (or table.unpack _G.unpack)
                rand (lcg 44)]
            (each [_ params (ipairs (or shape.params-tried [shape.params]))]
              (for [_ 1 200]
                (let [x (* 2 (- (* 2 (rand)) 1)) y (* 2 (- (* 2 (rand)) 1)) z (* 2 (- (* 2 (rand)) 1))
                      want (shape.reference x y z (unpack params))
                      args [x y z (unpack params)]
                      _ (table.insert args 1)
                      got (f (unpack args))]
                  ;; The same formulas, grouped alike but not always (a sum of
                  ;; squares, a mix): a few roundings of 1e-16 apart; 1e-9 is far
                  ;; above that and far below any wrong formula's error.
                  (assert.is_true (<= (math.abs (- got want)) (* 1e-9 (+ 1 (math.abs want))))
                                  (string.format "at %g %g %g (%s): translated %.17g, scalar %.17g"
                                                 x y z (table.concat params " ") got want))))))))

      (it (.. shape.name ": both texts pass the main process's checks, and the GLSL validates")
        (fn []
          (let [t (translated shape.source shape.tables)
                again (translated shape.source shape.tables)
                args (table.concat (fcollect [i 1 (+ (length shape.params) 1)] ", 1.0") "")
                (ok? out) (glslang (.. "#version 120\n" t.glsl
                                       "\nvoid main() { gl_FragColor = vec4(sdCustom(gl_FragCoord.xyz"
                                       args ")); }\n"))]
            (assert.are.equal t.glsl again.glsl)
            (assert.are.equal t.lua again.lua)
            (assert.is_true (custom.check-lua t.lua) t.lua)
            (assert.is_true (custom.check-glsl t.glsl t.glsl-name) t.glsl)
            (assert.is_true ok? (.. out "\n" t.glsl))))))

    (it "writes a loop counter's array item as a chain of selects, alike in both texts"
      (fn []
        (let [t (translated "(fn [x y z] (var d 0) (for [i 1 3] (set d (+ d (. [x y z] i)))) d)")]
          (assert.truthy (t.glsl:find "((v6 == 1.0) ? v0 : ((v6 == 2.0) ? v1 : v2))" 1 true) t.glsl)
          (assert.truthy (t.lua:find "(v6 == 1 and v0 or (v6 == 2 and v1 or v2))" 1 true) t.lua)
          (assert.are.equal 6 ((translate.compile-lua t.lua) 1 2 3 1)))))

    (it "breaks out of a loop past (math.min n K) and at &until, as Fennel's for does"
      (fn []
        (let [t (translated "(fn [x y z n]
  (var s 0)
  (for [i 1 (math.min n 6) &until (> s x)] (set s (+ s i)))
  s)")
              f (translate.compile-lua t.lua)
              fennel-f (fennel.eval "(fn [x y z n]
  (var s 0)
  (for [i 1 (math.min n 6) &until (> s x)] (set s (+ s i)))
  s)")]
          (assert.truthy (t.glsl:find "for (int i7 = 1; i7 <= 6; i7++) {" 1 true) t.glsl)
          (assert.truthy (t.glsl:find "if (v8 > v6) break;" 1 true) t.glsl)
          (assert.truthy (t.lua:find "for v8 = 1, 6 do" 1 true) t.lua)
          (each [_ [x n] (ipairs [[100 0] [100 2] [100 2.5] [100 6] [100 9] [2 9] [5 9] [-1 4]])]
            (assert.are.equal (fennel-f x 0 0 n) (f x 0 0 n 1) (.. x " " n))))))

    (it "raises each component to a whole power, and takes a vector from (values ...)"
      (fn []
        (let [t (translated "(fn [p] (let [(q k) (values (^ (- p 1) 3) 2)] (+ (. q 1) (* k (. q 2)) (. q 3))))")
              f (translate.compile-lua t.lua)]
          (assert.are.equal (+ (^ 1 3) (* 2 (^ -1 3)) (^ 3 3)) (f 2 0 4 1)))))

    (it "keeps a var's components apart when a new one reads an older (a swap)"
      (fn []
        (let [t (translated "(fn [x y z] (var v [x y z]) (set v [(. v 2) (. v 1) (. v 3)]) (set v (* v 2)) (+ (. v 1) (* 10 (. v 2)) (* 100 (. v 3))))")
              f (translate.compile-lua t.lua)]
          (assert.are.equal (+ 4 20 600) (f 1 2 3 1)))))

    (it "gives one GLSL function per kind of a helper's arguments"
      (fn []
        (let [t (translated "(fn [x y z] (fn twice [a] (* a 2)) (+ (twice x) (. (twice [y z]) 2) (. (twice [x y z]) 1) (twice y)))")]
          (assert.truthy (t.glsl:find "float sdCustomFn0(float v" 1 true) t.glsl)
          (assert.truthy (t.glsl:find "vec2 sdCustomFn1%(float v%d+, float v%d+%)") t.glsl)
          (assert.truthy (t.glsl:find "vec3 sdCustomFn2%(float v%d+, float v%d+, float v%d+%)") t.glsl)
          (assert.falsy (t.glsl:find "sdCustomFn3" 1 true) t.glsl)
          (assert.are.equal (+ 2 6 2 4) ((translate.compile-lua t.lua) 1 2 3 1)))))

    (it "refuses what is no vector form, with the line and what to write"
      (fn []
        (each [_ [source line expected ?tables]
               (ipairs [["(fn [p]\n (< p 1))" 2 "a vector of 3 numbers is used where a number is needed; take a component, (. v 1), or (length v) or (dot a b)"]
                        ["(fn [p]\n (length (+ p [1 2])))" 2 "(+ ...) mixes a vector of 3 numbers with one of 2; make them one size: [(. v 1) (. v 2)] is two of three"]
                        ["(fn [p]\n (math.min p [1 2]))" 2 "(math.min ...) mixes a vector of 3 numbers with one of 2"]
                        ["(fn [p] (abs p))" 1 "a distance function must give a number, not a vector of 3 numbers; take (length v) or a component (. v 1)"]
                        ["(fn [p]\n (dot p [1 2]))" 2 "(dot a b) takes two vectors of one size, got a vector of 3 numbers and a vector of 2 numbers"]
                        ["(fn [p]\n (dot p 1))" 2 "(dot a b) takes vectors; its argument 2 is a number"]
                        ["(fn [p]\n (length (cross [1 2] [3 4])))" 2 "(cross a b) takes two vectors of 3 numbers, got a vector of 2 numbers and a vector of 2 numbers"]
                        ["(fn [p]\n (length (normalize 2)))" 2 "(normalize v) takes vectors; its argument 1 is a number; for a number use (math.abs x)"]
                        ["(fn [p]\n\n (. p 4))" 3 "the index may be 4, outside a vector of 3 numbers (items 1 to 3)"]
                        ["(fn [p]\n (var d 0)\n (for [i 1 4] (set d (+ d (. p i))))\n d)" 3 "the index may be 1 to 4, outside a vector of 3 numbers (items 1 to 3)"]
                        ["(fn [p]\n (. p (math.floor (. p 1))))" 2 "an index must be known to stay in range: a whole constant, or a loop counter"]
                        ["(fn [p]\n (. (. p 1) 1))" 2 "(. v i) takes an item of a vector or an array; this is a number"]
                        ["(fn [p]\n (let [a [1 2 3 4]]\n (+ a 1)))" 3 "an array of 4 numbers is used as a value; arithmetic takes numbers and vectors: take an item, (. a i)"]
                        ["(fn [p]\n (let [a [1 2 3 4]]\n (+ (. p 1) a)))" 3 "an array of 4 numbers is used as a value"]
                        ["(fn [p]\n (. [[1 2] 3] 1))" 2 "an array mixes numbers and vectors; items are all numbers or all vectors of one size"]
                        ["(fn [p]\n (. [[1 2] [1 2 3]] 1 1))" 2 "an array mixes a vector of 2 numbers with one of 3"]
                        ["(fn [p]\n (. [] 1))" 2 "an empty [] has no value; a vector is [a b] or [a b c]"]
                        ["(fn [p]\n (. [(< 1 2) 1] 1))" 2 "an item of [...] is a comparison; items are numbers, or vectors of one size"]
                        ["(fn [p]\n (let [[a b c] [1 2]] a))" 2 "the pattern takes 3 items from a vector of 2 numbers"]
                        ["(fn [p]\n (var v [0 0 0])\n (set v 1)\n 1)" 3 "set gives a number to `v`, which holds a vector of 3 numbers; a var keeps its kind"]
                        ["(fn [p]\n (var v [0 0 0])\n (set v [1 2])\n 1)" 3 "set gives a vector of 2 numbers to `v`, which holds a vector of 3 numbers"]
                        ["(fn [p]\n (length (if (< (. p 1) 0) [1 2] 3)))" 2 "the branches of an if give different kinds or numbers of values"]
                        ["(fn [p]\n (if p 1 2))" 2 "a condition must be a comparison like (< a b); this is a vector of 3 numbers: compare its components, (< (. v 1) 0)"]
                        ["(fn [p]\n (+ p.x 1))" 2 "`p.x` is the field \"x\" of a table, nil for a vector [a b c] in Fennel; take its component: (. p 1)"]
                        ["(fn [p]\n (fn two [q] (values q q))\n (. (two p) 1))" 2 "gives 6 numbers; at most 4 (a vector counts its components)"]
                        ["(fn [p]\n (let [a [1 2 3 4 5]]\n (if (< (. p 1) 0) a a)))" 3 "an array of 5 numbers cannot be the value of an if or a function; bind it with local and take its items, (. a i)"]
                        ["(fn [x y z n m]\n (var d 0)\n (for [i 1 (math.min n m)] (set d (+ d i)))\n d)" 3 "a for loop's bounds must be whole constant numbers, or a stop of (math.min n K) for at most K turns, K a whole constant"]
                        ["(fn [x y z n]\n (var d 0)\n (for [i 1 (math.min n 65)] (set d (+ d i)))\n d)" 3 "a for loop may turn at most 64 times, this one turns 65 times"]
                        ["(fn [x y z]\n (var d 0)\n (for [i 1 3 &until d] (set d (+ d i)))\n d)" 3 "a condition must be a comparison like (< a b)"]
                        ["(fn [x y z]\n (var d 0)\n (for [i 1 3 &until (> d 1) 4] (set d (+ d i)))\n d)" 3 "(for [i start stop step &until c] ...) needs a name and two or three bounds (&until and its condition last)"]
                        ["(fn [p]\n (- (. sizes 1) 1))" 2 "`sizes` is a table that is not an array of numbers or of vectors [a b] or [a b c] (it has no items 1, 2, ...)" {:sizes {:small 1 :large 2}}]
                        ["(fn [p]\n (- (. sizes 1) 1))" 2 "(it has keys besides 1 to n)" {:sizes {1 1 2 2 :x 3}}]
                        ["(fn [p]\n (- (. sizes 1) 1))" 2 "`sizes` is a table that is not an array of numbers or of vectors [a b] or [a b c] (a vector item must be [a b] or [a b c])" {:sizes [[1 2 3 4]]}]
                        ["(fn [p]\n (- (. sizes 1) 1))" 2 "(an item is not a number)" {:sizes [1 "2"]}]
                        ["(fn [p q]\n 1)" 1 "a distance function takes the point first: (fn [x y z] ...), or as one vector (fn [p] ...); with parameters after a vector point, write (fn [x y z r] (let [p [x y z]] ...))"]])]
          (let [(ok? msg got-line) (translate.translate (parse source) {:resolve (resolver (or ?tables {}))})]
            (assert.is_nil ok? source)
            (assert.truthy (msg:find expected 1 true) (.. source "\n=> " (tostring msg)))
            (assert.are.equal line got-line (.. source ": line"))))))))

;;; The example scenes, through the app's loader.

(local examples
  {"examples/vector-box.fnl" [(fn [x y z] (- (ref-box x y z 0.6 0.4 0.5) 0.1))
                              (fn [x y z]
                                ;; From a (-0.5 -0.3 -0.5) to b (0.4 0.3 0.5), radius 0.3.
                                (let [bax 0.9 bay 0.6 baz 1
                                      pax (+ x 0.5) pay (+ y 0.3) paz (+ z 0.5)
                                      h (clamp (/ (+ (* pax bax) (* pay bay) (* paz baz))
                                                  (+ (* bax bax) (* bay bay) (* baz baz)))
                                               0 1)]
                                  (- (len3 (- pax (* h bax)) (- pay (* h bay)) (- paz (* h baz))) 0.3)))
                              (fn [x y z] (ref-round-cone x y z 0.45 0.2 0.9))]
   "examples/polygon-prism.fnl" [(fn [x y z]
                                   (ref-prism [[0 1] [-0.224 0.309] [-0.951 0.309] [-0.363 -0.118] [-0.588 -0.809]
                                               [0 -0.382] [0.588 -0.809] [0.363 -0.118] [0.951 0.309] [0.224 0.309]]
                                              x y z 0.3))]
   "examples/menger-fold.fnl" [(fn [x y z] (ref-menger x y z 3))]})

(describe "the example scenes of vectors"
  (fn []
    (each [_ file (ipairs ["examples/vector-box.fnl" "examples/polygon-prism.fnl" "examples/menger-fold.fnl"])]
      (it (.. file ": loads, each custom node computing what the scalar implementation does")
        (fn []
          (let [scene (assert (load.load-file file))
                nodes (icollect [_ o (ipairs scene.objects)] (when (?. o :tree :custom) o.tree))
                refs (. examples file)
                rand (lcg 7)]
            (assert.are.equal (length refs) (length nodes))
            (each [k node (ipairs nodes)]
              (let [desc (custom.descriptor node)
                    args (desc.pack node)
                    unpack (or table.unpack _G.unpack)]
                ;; Exact distances: no factor divides them.
                (assert.are.equal 1 node.lipschitz)
                (for [_ 1 200]
                  (let [x (* 1.5 (- (* 2 (rand)) 1)) y (* 1.5 (- (* 2 (rand)) 1)) z (* 1.5 (- (* 2 (rand)) 1))
                        want ((. refs k) x y z)
                        got (desc.cpu x y z (unpack args))]
                    ;; As above: the same formulas, a few roundings apart.
                    (assert.is_true (<= (math.abs (- got want)) (* 1e-9 (+ 1 (math.abs want))))
                                    (string.format "%s node %d at %g %g %g: %.17g, scalar %.17g"
                                                   file k x y z got want))))))))))))
