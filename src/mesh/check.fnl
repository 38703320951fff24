;; Checks of a triangle mesh (what a printer or modeller needs): closed and 2-manifold
;; with one orientation, its enclosed volume, and how far its vertices are from a
;; distance field's surface. A mesh is {:positions [x y z ...] :triangles [a b c ...]}
;; (1-based vertex indices). Pure: runs under plain LuaJIT.

;; `pairs` under another name: a loop over `pairs` by that name is LuaJIT's ITERN,
;; which Debian 12's LuaJIT ends early once despecialised (see src/util/wire.fnl).
(local each-pair pairs)

(local sqrt math.sqrt)

(fn edge-key [a b n] (+ (* a (+ n 1)) b))

(fn topology [m]
  "What keeps mesh `m` from being a closed oriented 2-manifold:
{:triangles :vertices :edges :boundary (edges of one triangle) :non-manifold (edges of
three or more) :misoriented (edges whose two triangles run it the same way)
:degenerate (triangles repeating a vertex) :pinched (vertices whose triangles do not
form one fan closed around them) :unused (vertices of no triangle) :closed? (no
boundary, no non-manifold edge) :manifold? (closed, oriented, no degenerate
triangle, no pinched vertex) :euler (V - E + F)}."
  (let [tris m.triangles
        nv (/ (length m.positions) 3)
        nt (/ (length tris) 3)
        ;; Directed edge -> count, undirected edge -> count.
        directed {}
        undirected {}
        ;; Per vertex: the link, each opposite edge b -> c of its triangles.
        link {}]
    (var degenerate 0)
    (for [t 0 (- nt 1)]
      (let [a (. tris (+ (* 3 t) 1)) b (. tris (+ (* 3 t) 2)) c (. tris (+ (* 3 t) 3))]
        (if (or (= a b) (= b c) (= a c))
            (set degenerate (+ degenerate 1))
            (each [_ [p q r] (ipairs [[a b c] [b c a] [c a b]])]
              (let [dk (edge-key p q nv)
                    uk (edge-key (math.min p q) (math.max p q) nv)]
                (tset directed dk (+ 1 (or (. directed dk) 0)))
                (tset undirected uk (+ 1 (or (. undirected uk) 0)))
                (when (not (. link p)) (tset link p []))
                (table.insert (. link p) q)
                (table.insert (. link p) r))))))
    (var (edges boundary non-manifold misoriented) (values 0 0 0 0))
    (each [uk n (each-pair undirected)]
      (set edges (+ edges 1))
      (if (= n 1) (set boundary (+ boundary 1))
          (> n 2) (set non-manifold (+ non-manifold 1))
          (let [a (math.floor (/ uk (+ nv 1))) b (% uk (+ nv 1))]
            (when (not= 1 (or (. directed (edge-key a b nv)) 0))
              (set misoriented (+ misoriented 1))))))
    ;; A vertex is pinched when its link (the opposite edges of its triangles) is not
    ;; one cycle: two fans meeting at a point.
    (var (pinched unused) (values 0 0))
    (for [v 1 nv]
      (let [l (. link v)]
        (if (not l) (set unused (+ unused 1))
            (let [next-of {}
                  count (/ (length l) 2)]
              (var ok? true)
              (for [s 1 (length l) 2]
                (let [b (. l s) c (. l (+ s 1))]
                  (if (. next-of b) (set ok? false) (tset next-of b c))))
              ;; Walk from the first: one cycle returns to it after every link edge,
              ;; and not before.
              (when ok?
                (let [start (. l 1)]
                  (var at start)
                  (for [s 1 count &until (not ok?)]
                    (set at (. next-of at))
                    (when (or (= at nil) (and (= at start) (< s count)))
                      (set ok? false)))
                  (set ok? (and ok? (= at start)))))
              (when (not ok?) (set pinched (+ pinched 1)))))))
    (let [closed? (and (= boundary 0) (= non-manifold 0))]
      {:triangles nt :vertices nv : edges : boundary : non-manifold : misoriented
       : degenerate : pinched : unused : closed?
       :manifold? (and closed? (= misoriented 0) (= degenerate 0) (= pinched 0))
       :euler (+ (- nv edges) nt)})))

(fn volume [m]
  "The signed volume mesh `m` encloses (positive when its triangles run
counter-clockwise seen from outside)."
  (let [p m.positions tris m.triangles]
    (var v 0)
    (for [t 1 (length tris) 3]
      (let [a (* 3 (- (. tris t) 1)) b (* 3 (- (. tris (+ t 1)) 1)) c (* 3 (- (. tris (+ t 2)) 1))
            ax (. p (+ a 1)) ay (. p (+ a 2)) az (. p (+ a 3))
            bx (. p (+ b 1)) by (. p (+ b 2)) bz (. p (+ b 3))
            cx (. p (+ c 1)) cy (. p (+ c 2)) cz (. p (+ c 3))]
        (set v (+ v (* ax (- (* by cz) (* bz cy))) (* ay (- (* bz cx) (* bx cz)))
                  (* az (- (* bx cy) (* by cx)))))))
    (/ v 6)))

(fn area [m]
  "The surface area of mesh `m`."
  (let [p m.positions tris m.triangles]
    (var s 0)
    (for [t 1 (length tris) 3]
      (let [a (* 3 (- (. tris t) 1)) b (* 3 (- (. tris (+ t 1)) 1)) c (* 3 (- (. tris (+ t 2)) 1))
            ux (- (. p (+ b 1)) (. p (+ a 1))) uy (- (. p (+ b 2)) (. p (+ a 2)))
            uz (- (. p (+ b 3)) (. p (+ a 3)))
            vx (- (. p (+ c 1)) (. p (+ a 1))) vy (- (. p (+ c 2)) (. p (+ a 2)))
            vz (- (. p (+ c 3)) (. p (+ a 3)))
            x (- (* uy vz) (* uz vy)) y (- (* uz vx) (* ux vz)) z (- (* ux vy) (* uy vx))]
        (set s (+ s (* 0.5 (sqrt (+ (* x x) (* y y) (* z z))))))))
    s))

(fn surface-distance [m distance]
  "The largest |distance x y z| over the vertices of mesh `m` and the vertex (1-based)
where it is."
  (let [p m.positions]
    (var (worst at) (values 0 nil))
    (for [v 1 (/ (length p) 3)]
      (let [b (* 3 (- v 1))
            d (math.abs (distance (. p (+ b 1)) (. p (+ b 2)) (. p (+ b 3))))]
        (when (> d worst) (set (worst at) (values d v)))))
    (values worst at)))

(fn triangles-distance [m values-of spacing]
  "The largest |value| of the field `values-of` (fn [flat] -> values at the points
x y z ...) over mesh `m`'s triangles, each read at the points of a barycentric grid
at most `spacing` apart (at least 4 divisions a side, corners included), and the
point [x y z] where it is."
  (let [p m.positions tris m.triangles]
    (var (worst at) (values 0 nil))
    (fn measure! [flat]
      (each [i d (ipairs (values-of flat))]
        (when (> (math.abs d) worst)
          (set (worst at) (values (math.abs d) [(. flat (- (* 3 i) 2)) (. flat (- (* 3 i) 1))
                                                (. flat (* 3 i))])))))
    (var flat [])
    (for [t 1 (length tris) 3]
      (let [a (* 3 (- (. tris t) 1)) b (* 3 (- (. tris (+ t 1)) 1)) c (* 3 (- (. tris (+ t 2)) 1))
            side (fn [i j] (sqrt (+ (^ (- (. p (+ i 1)) (. p (+ j 1))) 2)
                                    (^ (- (. p (+ i 2)) (. p (+ j 2))) 2)
                                    (^ (- (. p (+ i 3)) (. p (+ j 3))) 2))))
            k (math.max 4 (math.ceil (/ (math.max (side a b) (side b c) (side c a)) spacing)))]
        (for [i 0 k]
          (for [j 0 (- k i)]
            (let [wa (/ i k) wb (/ j k) wc (/ (- k i j) k)]
              (for [q 1 3]
                (table.insert flat (+ (* wa (. p (+ a q))) (* wb (. p (+ b q)))
                                      (* wc (. p (+ c q)))))))))
        (when (> (length flat) 98304)
          (measure! flat)
          (set flat []))))
    (measure! flat)
    (values worst at)))

(fn describe [t]
  "One line about topology `t`."
  (string.format "%d triangles, %d vertices: %d boundary edges, %d non-manifold edges, %d misoriented, %d degenerate triangles, %d pinched vertices, Euler characteristic %d"
                 t.triangles t.vertices t.boundary t.non-manifold t.misoriented t.degenerate
                 t.pinched t.euler))

{: topology : volume : area : surface-distance : triangles-distance : describe}
