;; Mesh files, for printing a scene or taking it into another modelling program: binary
;; STL (triangles only), binary little-endian PLY and Wavefront OBJ (both with a colour
;; per vertex: PLY as red green blue bytes, OBJ as the common `v x y z r g b` extension
;; that MeshLab, Blender and trimesh read), and readers for the same, so that a written
;; file can be checked by parsing it back. A mesh is {:positions [x y z ...] :triangles
;; [a b c ...] (1-based) :colors [r g b ...] (0-1 per vertex, optional)}. Pure: plain
;; LuaJIT (its FFI packs the floats).

(local ffi (require :ffi))

(local extensions {:stl :stl :ply :ply :obj :obj})

(fn format-of [path]
  "The format :stl, :ply or :obj named by the extension of `path` (any case), or nil
and a message."
  (let [ext (path:match "%.([%w]+)$")
        f (and ext (. extensions (ext:lower)))]
    (if f f
        (values nil (.. "--out must name a .stl, .ply or .obj file, got " path)))))

;;; Binary packing: little-endian, as STL and the PLY header below declare.

(local little? (ffi.abi :le))
(local f32 (ffi.new "float[1]"))
(local u32 (ffi.new "uint32_t[1]"))
(local u16 (ffi.new "uint16_t[1]"))

(fn ordered [s]
  (if little? s (s:reverse)))

(fn pack-float [v]
  (tset f32 0 v)
  (ordered (ffi.string f32 4)))

(fn pack-u32 [v]
  (tset u32 0 v)
  (ordered (ffi.string u32 4)))

(fn pack-u16 [v]
  (tset u16 0 v)
  (ordered (ffi.string u16 2)))

(fn read-float [s i]
  (ffi.copy f32 (ordered (s:sub i (+ i 3))) 4)
  (tonumber (. f32 0)))

(fn read-u32 [s i]
  (ffi.copy u32 (ordered (s:sub i (+ i 3))) 4)
  (tonumber (. u32 0)))

(fn byte-colour [v]
  (math.floor (+ 0.5 (* 255 (math.max 0 (math.min 1 (or v 0)))))))

(fn triangle-normal [p a b c]
  (let [a (* 3 (- a 1)) b (* 3 (- b 1)) c (* 3 (- c 1))
        ux (- (. p (+ b 1)) (. p (+ a 1))) uy (- (. p (+ b 2)) (. p (+ a 2)))
        uz (- (. p (+ b 3)) (. p (+ a 3)))
        vx (- (. p (+ c 1)) (. p (+ a 1))) vy (- (. p (+ c 2)) (. p (+ a 2)))
        vz (- (. p (+ c 3)) (. p (+ a 3)))
        x (- (* uy vz) (* uz vy)) y (- (* uz vx) (* ux vz)) z (- (* ux vy) (* uy vx))
        l (math.sqrt (+ (* x x) (* y y) (* z z)))]
    (if (> l 0) (values (/ x l) (/ y l) (/ z l)) (values 0 0 0))))

;;; Writers.

(fn stl [m ?name]
  (let [p m.positions tris m.triangles
        header (.. "binary STL from fennel-raymarcher --mesh " (or ?name ""))
        out [(.. (header:sub 1 80) (string.rep " " (- 80 (math.min 80 (length header)))))
             (pack-u32 (/ (length tris) 3))]]
    (for [t 1 (length tris) 3]
      (let [a (. tris t) b (. tris (+ t 1)) c (. tris (+ t 2))
            (nx ny nz) (triangle-normal p a b c)]
        (table.insert out (.. (pack-float nx) (pack-float ny) (pack-float nz)))
        (each [_ v (ipairs [a b c])]
          (let [k (* 3 (- v 1))]
            (table.insert out (.. (pack-float (. p (+ k 1))) (pack-float (. p (+ k 2)))
                                  (pack-float (. p (+ k 3)))))))
        (table.insert out (pack-u16 0))))
    (table.concat out)))

(fn ply [m ?name]
  (let [p m.positions tris m.triangles cs m.colors
        nv (/ (length p) 3) nt (/ (length tris) 3)
        out [(table.concat
              ["ply" "format binary_little_endian 1.0"
               (.. "comment fennel-raymarcher --mesh " (or ?name ""))
               (.. "element vertex " nv)
               "property float x" "property float y" "property float z"
               "property uchar red" "property uchar green" "property uchar blue"
               (.. "element face " nt) "property list uchar int vertex_indices"
               "end_header" ""] "\n")]]
    (for [v 0 (- nv 1)]
      (let [k (* 3 v)]
        (table.insert out (.. (pack-float (. p (+ k 1))) (pack-float (. p (+ k 2)))
                              (pack-float (. p (+ k 3)))
                              (string.char (byte-colour (and cs (. cs (+ k 1))))
                                           (byte-colour (and cs (. cs (+ k 2))))
                                           (byte-colour (and cs (. cs (+ k 3)))))))))
    (for [t 1 (length tris) 3]
      (table.insert out (.. "\3" (pack-u32 (- (. tris t) 1)) (pack-u32 (- (. tris (+ t 1)) 1))
                            (pack-u32 (- (. tris (+ t 2)) 1)))))
    (table.concat out)))

(fn obj [m ?name]
  (let [p m.positions tris m.triangles cs m.colors
        out [(.. "# fennel-raymarcher --mesh " (or ?name "") "\n")
             "# v x y z r g b (colour 0-1 per vertex); f a b c counter-clockwise from outside\n"]]
    (for [k 0 (- (length p) 1) 3]
      (table.insert out (if cs
                            (string.format "v %.9g %.9g %.9g %.4f %.4f %.4f\n"
                                           (. p (+ k 1)) (. p (+ k 2)) (. p (+ k 3))
                                           (. cs (+ k 1)) (. cs (+ k 2)) (. cs (+ k 3)))
                            (string.format "v %.9g %.9g %.9g\n"
                                           (. p (+ k 1)) (. p (+ k 2)) (. p (+ k 3))))))
    (for [t 1 (length tris) 3]
      (table.insert out (string.format "f %d %d %d\n" (. tris t) (. tris (+ t 1))
                                       (. tris (+ t 2)))))
    (table.concat out)))

(fn encode [m format ?name]
  "The bytes of mesh `m` in `format` (:stl, :ply or :obj); `?name` goes in the header."
  (case format
    :stl (stl m ?name)
    :ply (ply m ?name)
    :obj (obj m ?name)))

;;; Readers: the files above (and others of their shape) back into meshes.

(fn read-stl [s]
  (if (< (length s) 84) (values nil "STL: shorter than its 84-byte header")
      (let [n (read-u32 s 81)]
        (if (not= (length s) (+ 84 (* 50 n)))
            (values nil (string.format "STL: %d triangles need %d bytes, the file has %d"
                                       n (+ 84 (* 50 n)) (length s)))
            ;; Triangle soup: corners at the same position are one vertex.
            (let [positions [] triangles [] seen {}]
              (for [t 0 (- n 1)]
                (for [c 0 2]
                  (let [at (+ 84 (* 50 t) 12 (* 12 c) 1)
                        x (read-float s at) y (read-float s (+ at 4)) z (read-float s (+ at 8))
                        key (s:sub at (+ at 11))]
                    (when (not (. seen key))
                      (table.insert positions x) (table.insert positions y)
                      (table.insert positions z)
                      (tset seen key (/ (length positions) 3)))
                    (table.insert triangles (. seen key)))))
              {: positions : triangles})))))

(fn read-ply [s]
  (let [(header-end body) (s:find "end_header\n" 1 true)]
    (if (not header-end) (values nil "PLY: no end_header line")
        (let [header (s:sub 1 header-end)
              nv (tonumber (header:match "element vertex (%d+)"))
              nt (tonumber (header:match "element face (%d+)"))
              props (icollect [t name (header:gmatch "property (%a+) (%a+)\n")] name)]
          (if (not (header:match "^ply\nformat binary_little_endian 1.0\n"))
              (values nil "PLY: not binary_little_endian 1.0")
              (or (not nv) (not nt)
                  (not= (table.concat props " ") "x y z red green blue"))
              (values nil "PLY: expected vertices of x y z red green blue and a face list")
              (let [positions [] colors [] triangles []]
                (var at (+ body 1))
                (for [_ 1 nv]
                  (for [k 0 2] (table.insert positions (read-float s (+ at (* 4 k)))))
                  (for [k 0 2] (table.insert colors (/ (s:byte (+ at 12 k)) 255)))
                  (set at (+ at 15)))
                (var err nil)
                (for [_ 1 nt &until err]
                  (if (not= (s:byte at) 3) (set err "PLY: a face that is not a triangle")
                      (do (for [k 0 2]
                            (table.insert triangles (+ 1 (read-u32 s (+ at 1 (* 4 k))))))
                          (set at (+ at 13)))))
                (if err (values nil err)
                    (not= at (+ (length s) 1)) (values nil "PLY: bytes after the last face")
                    {: positions : colors : triangles})))))))

(fn read-obj [s]
  (let [positions [] colors [] triangles []]
    (var err nil)
    (var line-no 0)
    (each [line (s:gmatch "([^\n]*)\n?") &until err]
      (set line-no (+ line-no 1))
      (let [words (icollect [w (line:gmatch "%S+")] w)]
        (case (. words 1)
          :v (let [nums (fcollect [k 2 (length words)] (tonumber (. words k)))]
               (for [k 1 3] (table.insert positions (. nums k)))
               (when (= (length nums) 6)
                 (for [k 4 6] (table.insert colors (. nums k)))))
          :f (if (not= (length words) 4)
                 (set err (string.format "OBJ:%d: a face that is not a triangle" line-no))
                 (for [k 2 4]
                   (table.insert triangles (tonumber (: (. words k) :match "^(%d+)"))))))))
    (if err (values nil err)
        {: positions : triangles
         :colors (when (= (length colors) (length positions)) colors)})))

(fn decode [s format]
  "The mesh in the bytes `s` of `format` (:stl, :ply or :obj), or nil and a message."
  (case format
    :stl (read-stl s)
    :ply (read-ply s)
    :obj (read-obj s)))

{: format-of : encode : decode}
