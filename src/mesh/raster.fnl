;; A picture of a triangle mesh, for docs/mesh.md and for looking at an exported file
;; without another program: a software rasteriser with a depth buffer, each triangle
;; flat-shaded in its vertices' mean colour (grey without colours) by a light over the
;; viewer's shoulder, its edges drawn faintly so the triangles show. Pure: plain LuaJIT
;; (FFI buffers).

(local ffi (require :ffi))

(local sqrt math.sqrt)
(local rad math.rad)

(fn bounds [p]
  (let [lo [math.huge math.huge math.huge] hi [(- math.huge) (- math.huge) (- math.huge)]]
    (for [k 0 (- (length p) 1) 3]
      (for [c 1 3]
        (tset lo c (math.min (. lo c) (. p (+ k c))))
        (tset hi c (math.max (. hi c) (. p (+ k c))))))
    (values lo hi)))

(fn picture [m ?options]
  "An RGBA image {:width :height :pixels} (as src/util/png.fnl encodes) of mesh `m`
seen from `:yaw` and `:pitch` degrees (default 35 and 25: from the front right,
above; z is up) at `:width` x `:height` (640 x 480), framed on its bounding box
(`:zoom` 0.8: the share of the bounding sphere's radius that fills half the
picture's shorter side, less than 1 when the box is emptier than its sphere)."
  (let [o (or ?options {})
        w (or o.width 640) h (or o.height 480)
        p m.positions tris m.triangles cs m.colors
        (lo hi) (bounds p)
        centre (fcollect [c 1 3] (* 0.5 (+ (. lo c) (. hi c))))
        radius (* 0.5 (sqrt (accumulate [s 0 c (ipairs [1 2 3])]
                              (+ s (^ (- (. hi c) (. lo c)) 2)))))
        yaw (rad (or o.yaw 35)) pitch (rad (or o.pitch 25))
        ;; The camera looks along -f from the centre's side f, right r, up u.
        fx (* (math.cos pitch) (math.sin yaw)) fy (* -1 (math.cos pitch) (math.cos yaw))
        fz (math.sin pitch)
        rx (math.cos yaw) ry (math.sin yaw) rz 0
        ux (- (* fy rz) (* fz ry)) uy (- (* fz rx) (* fx rz)) uz (- (* fx ry) (* fy rx))
        ;; Negated: up is the one with a positive z.
        (ux uy uz) (if (< uz 0) (values (- ux) (- uy) (- uz)) (values ux uy uz))
        dist (* 3.2 radius)
        focal (* 0.5 (math.min w h) (/ dist (* (or o.zoom 0.8) radius)))
        ;; Light from above the camera's right shoulder.
        (lx ly lz) (let [x (+ fx (* 0.5 rx) (* 0.8 ux)) y (+ fy (* 0.5 ry) (* 0.8 uy))
                         z (+ fz (* 0.5 rz) (* 0.8 uz)) l (sqrt (+ (* x x) (* y y) (* z z)))]
                     (values (/ x l) (/ y l) (/ z l)))
        nv (/ (length p) 3)
        sx (ffi.new "double[?]" (+ nv 1)) sy (ffi.new "double[?]" (+ nv 1))
        sz (ffi.new "double[?]" (+ nv 1))
        depth (ffi.new "double[?]" (* w h))
        pixels (ffi.new "uint8_t[?]" (* w h 4))]
    ;; Background: a soft vertical gradient.
    (for [y 0 (- h 1)]
      (let [t (/ y h)]
        (for [x 0 (- w 1)]
          (let [i (* 4 (+ x (* y w)))]
            (tset pixels i (math.floor (+ 232 (* -30 t))))
            (tset pixels (+ i 1) (math.floor (+ 236 (* -28 t))))
            (tset pixels (+ i 2) (math.floor (+ 242 (* -22 t))))
            (tset pixels (+ i 3) 255)
            (tset depth (+ x (* y w)) math.huge)))))
    (for [v 1 nv]
      (let [k (* 3 (- v 1))
            qx (- (. p (+ k 1)) (. centre 1)) qy (- (. p (+ k 2)) (. centre 2))
            qz (- (. p (+ k 3)) (. centre 3))
            ;; Camera space: along r, along u, and the depth from the camera.
            cx (+ (* qx rx) (* qy ry) (* qz rz))
            cy (+ (* qx ux) (* qy uy) (* qz uz))
            cz (- dist (+ (* qx fx) (* qy fy) (* qz fz)))]
        (tset sx v (+ (* 0.5 w) (/ (* focal cx) cz)))
        (tset sy v (- (* 0.5 h) (/ (* focal cy) cz)))
        (tset sz v cz)))
    (for [t 1 (length tris) 3]
      (let [a (. tris t) b (. tris (+ t 1)) c (. tris (+ t 2))
            ax (. sx a) ay (. sy a) bx (. sx b) by (. sy b) cx (. sx c) cy (. sy c)
            area (- (* (- bx ax) (- cy ay)) (* (- by ay) (- cx ax)))]
        ;; Counter-clockwise from outside is clockwise on screen (y down): only
        ;; triangles facing the camera have a negative area here.
        (when (< area 0)
          (let [ka (* 3 (- a 1)) kb (* 3 (- b 1)) kc (* 3 (- c 1))
                ex1 (- (. p (+ kb 1)) (. p (+ ka 1))) ey1 (- (. p (+ kb 2)) (. p (+ ka 2)))
                ez1 (- (. p (+ kb 3)) (. p (+ ka 3)))
                ex2 (- (. p (+ kc 1)) (. p (+ ka 1))) ey2 (- (. p (+ kc 2)) (. p (+ ka 2)))
                ez2 (- (. p (+ kc 3)) (. p (+ ka 3)))
                nx (- (* ey1 ez2) (* ez1 ey2)) ny (- (* ez1 ex2) (* ex1 ez2))
                nz (- (* ex1 ey2) (* ey1 ex2))
                nl (sqrt (+ (* nx nx) (* ny ny) (* nz nz)))
                lambert (if (> nl 0) (math.max 0 (/ (+ (* nx lx) (* ny ly) (* nz lz)) nl)) 0)
                shade (+ 0.3 (* 0.7 lambert))
                colour (fn [q] (if cs (/ (+ (. cs (+ ka q)) (. cs (+ kb q)) (. cs (+ kc q))) 3) 0.75))
                r (* 255 shade (colour 1)) g (* 255 shade (colour 2)) bl (* 255 shade (colour 3))
                x0 (math.max 0 (math.floor (math.min ax bx cx)))
                x1 (math.min (- w 1) (math.ceil (math.max ax bx cx)))
                y0 (math.max 0 (math.floor (math.min ay by cy)))
                y1 (math.min (- h 1) (math.ceil (math.max ay by cy)))
                za (. sz a) zb (. sz b) zc (. sz c)
                ;; Each edge's length, to measure a pixel's distance to it.
                la (sqrt (+ (^ (- cx bx) 2) (^ (- cy by) 2)))
                lb (sqrt (+ (^ (- ax cx) 2) (^ (- ay cy) 2)))
                lc (sqrt (+ (^ (- bx ax) 2) (^ (- by ay) 2)))]
            (for [y y0 y1]
              (for [x x0 x1]
                (let [px (+ x 0.5) py (+ y 0.5)
                      ;; Barycentric weights (the area is negative, so are these inside).
                      wa (/ (- (* (- bx px) (- cy py)) (* (- by py) (- cx px))) area)
                      wb (/ (- (* (- cx px) (- ay py)) (* (- cy py) (- ax px))) area)
                      wc (- 1 wa wb)]
                  (when (and (>= wa 0) (>= wb 0) (>= wc 0))
                    (let [z (+ (* wa za) (* wb zb) (* wc zc))
                          i (+ x (* y w))]
                      (when (< z (. depth i))
                        (tset depth i z)
                        ;; Pixels within about half a pixel of an edge are darker.
                        (let [edge (math.min (* wa (/ (math.abs area) (math.max la 1e-9)))
                                             (* wb (/ (math.abs area) (math.max lb 1e-9)))
                                             (* wc (/ (math.abs area) (math.max lc 1e-9))))
                              k (if (< edge 0.6) 0.8 1)
                              q (* 4 i)]
                          (tset pixels q (math.min 255 (math.floor (* k r))))
                          (tset pixels (+ q 1) (math.min 255 (math.floor (* k g))))
                          (tset pixels (+ q 2) (math.min 255 (math.floor (* k bl)))))))))))))))
    {:width w :height h : pixels :alpha? false}))

{: picture}
