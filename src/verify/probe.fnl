;; Probing the distance field: points in, the scene's signed distance and material out.
;; `love . --probe SCENE` prints what the CPU evaluator gives; with --gpu the same
;; points go through the generated GLSL (src/backend/probe.fnl), one pixel per point,
;; so anyone can compare the two. Pure: runs under plain LuaJIT.

(local reference (require :src.verify.reference))

(local max-points 1000000)

(fn parse-number [s]
  (let [v (tonumber s)]
    (and v (= v v) (not= v math.huge) (not= v (- math.huge)) v)))

(fn parse-points [text ?name]
  "Points from `text`, one `x y z` per line (world coordinates; blank lines and lines
starting with # are skipped). Returns a list of [x y z], or nil and a message naming
the line."
  (let [name (or ?name "stdin")
        points []]
    (var err nil)
    (var line-no 0)
    (each [line (: (.. text "\n") :gmatch "([^\n]*)\n") &until err]
      (set line-no (+ line-no 1))
      (let [line (line:gsub "\r$" "")]
        (when (not (or (line:match "^%s*$") (line:match "^%s*#")))
          (let [fields (icollect [w (line:gmatch "%S+")] w)
                nums (icollect [_ w (ipairs fields)] (parse-number w))]
            (if (or (not= (length fields) 3) (not= (length nums) 3))
                (set err (string.format "%s:%d: expected three finite numbers `x y z`, got %q"
                                        name line-no (if (> (length line) 60)
                                                         (.. (line:sub 1 60) "...")
                                                         line)))
                (>= (length points) max-points)
                (set err (.. name ":" line-no ": at most " max-points " points"))
                (table.insert points nums))))))
    (if err (values nil err) points)))

(fn cpu-values [scene plan points]
  "For each point: {:distance d :color [r g b] :mirror m} from the CPU evaluator
(the distance is capped at the draw distance, as the shader's)."
  (let [T (reference.tracer scene plan)]
    (icollect [_ [x y z] (ipairs points)]
      (let [(d _ r g b m) (T.map-color x y z)]
        {:distance d :color [r g b] :mirror m}))))

(fn format-line [v]
  "One output line: distance, then the material's colour and mirror amount."
  (string.format "%.9g %.6g %.6g %.6g %.6g" v.distance (. v.color 1) (. v.color 2)
                 (. v.color 3) v.mirror))

{: parse-points : cpu-values : format-line}
