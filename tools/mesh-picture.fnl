;; A picture of a mesh file written by `love . --mesh` (issue 31), under plain LuaJIT:
;;   luajit tools/fnl.lua tools/mesh-picture.fnl FILE.ply|.obj|.stl OUT.png [WxH] [YAW PITCH]
;; flat-shaded triangles in the file's vertex colours (grey for STL), their edges
;; faint (src/mesh/raster.fnl). docs/mesh.md's pictures of exported meshes are made so.

(local formats (require :src.mesh.formats))
(local raster (require :src.mesh.raster))
(local png (require :src.util.png))

(fn fail [msg]
  (io.stderr:write (.. "mesh-picture: " msg "\n"))
  (os.exit 1))

(let [[path out size yaw pitch] arg
      _ (when (not (and path out)) (fail "usage: mesh-picture.fnl FILE OUT.png [WxH] [YAW PITCH]"))
      format (or (formats.format-of path) (fail (.. "not a mesh file: " path)))
      bytes (with-open [f (or (io.open path :rb) (fail (.. "cannot read " path)))] (f:read "*a"))
      (m err) (formats.decode bytes format)
      _ (when (not m) (fail err))
      (w h) (when size (size:match "^(%d+)x(%d+)$"))
      image (raster.picture m {:width (tonumber w) :height (tonumber h)
                               :yaw (tonumber yaw) :pitch (tonumber pitch)})]
  (case (png.write-file out image)
    true (print (string.format "wrote %s (%dx%d, %d triangles)" out image.width image.height
                               (/ (length m.triangles) 3)))
    (nil e) (fail e)))
