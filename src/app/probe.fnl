;; Probing the distance field: points in, the scene's signed distance and material out.
;; `love . --probe SCENE` prints what the CPU evaluator gives; with --gpu the same
;; points go through the generated GLSL (src/backend/probe.fnl), one pixel per point,
;; so anyone can compare the two. Input is read in fixed-size chunks and answered in
;; batches, so an endless stream runs in constant memory. Pure: runs under plain LuaJIT.

(local reference (require :src.reference))

;; A point is three numbers: a line longer than this is refused before it is read whole.
(local max-line 4096)
;; Bytes per read, and points per batch answered.
(local chunk-size 65536)
(local batch-size 16384)

(fn parse-number [s]
  ;; nil (never false, which icollect would keep) unless `s` is a finite number.
  (let [v (tonumber s)]
    (when (and v (= v v) (not= v math.huge) (not= v (- math.huge))) v)))

(fn parse-line [line name line-no]
  "The point [x y z] on `line`, false for a blank or comment line, or nil and a
message naming the line."
  (let [line (line:gsub "\r$" "")]
    (if (or (line:match "^%s*$") (line:match "^%s*#"))
        false
        (let [fields (icollect [w (line:gmatch "%S+")] w)
              nums (icollect [_ w (ipairs fields)] (parse-number w))]
          (if (or (not= (length fields) 3) (not= (length nums) 3))
              (values nil (string.format "%s:%d: expected three finite numbers `x y z`, got %q"
                                         name line-no (if (> (length line) 60)
                                                          (.. (line:sub 1 60) "...")
                                                          line)))
              nums)))))

(fn point-reader [file ?name ?options]
  "A function that returns the next batch of points read from `file` (anything with
`file:read n`, as io.stdin; `?name` names it in messages, default \"stdin\"): a list
of up to :batch points [x y z] (world coordinates; blank lines and lines starting
with # are skipped), nil at the end, or nil and a message naming the line. Every
point before a bad line is returned before its message. Options: :batch (points per
batch, 16384), :max-line (bytes, 4096: a longer line is refused as soon as that many
bytes are read) and :chunk (bytes per read, 65536). Memory stays within a chunk, a
line and a batch however long the input."
  (let [name (or ?name "stdin")
        options (or ?options {})
        batch (or options.batch batch-size)
        limit (or options.max-line max-line)
        chunk-bytes (or options.chunk chunk-size)
        too-long (fn [line-no]
                   (string.format "%s:%d: line longer than %d bytes; a point is three numbers `x y z`"
                                  name line-no limit))]
    (var chunk "")
    (var pos 1)
    ;; The start of a line whose end is in a later chunk.
    (var head "")
    (var line-no 0)
    (var eof? false)
    (var err nil)
    (fn take-line! [line points]
      (set line-no (+ line-no 1))
      (if (> (length line) limit)
          (set err (too-long line-no))
          (let [(point msg) (parse-line line name line-no)]
            (if point (table.insert points point)
                (= point nil) (set err msg)))))
    (fn []
      (let [points []]
        (while (and (not err) (not eof?) (< (length points) batch))
          (if (> pos (length chunk))
              (case (file:read chunk-bytes)
                text (set (chunk pos) (values text 1))
                _ (do (set eof? true)
                      (when (> (length head) 0) (take-line! head points))
                      (set head "")))
              (case (chunk:find "\n" pos true)
                nl (let [line (.. head (chunk:sub pos (- nl 1)))]
                     (set (head pos) (values "" (+ nl 1)))
                     (take-line! line points))
                _ (do (set head (.. head (chunk:sub pos)))
                      (set pos (+ (length chunk) 1))
                      (when (> (length head) limit)
                        (set err (too-long (+ line-no 1))))))))
        (if (> (length points) 0) points
            err (values nil err)
            nil)))))

(fn text-file [text]
  ;; A string read as a file, for parse-points.
  (var pos 1)
  {:read (fn [_ n]
           (when (<= pos (length text))
             (let [s (text:sub pos (+ pos n -1))]
               (set pos (+ pos n))
               s)))})

(fn parse-points [text ?name]
  "Points from `text`, one `x y z` per line (world coordinates; blank lines and lines
starting with # are skipped). Returns a list of [x y z], or nil and a message naming
the line."
  (let [next-batch (point-reader (text-file text) ?name)
        points []]
    (var (done? err) false)
    (while (not done?)
      (case (next-batch)
        batch (each [_ p (ipairs batch)] (table.insert points p))
        (nil ?msg) (set (done? err) (values true ?msg))))
    (if err (values nil err) points)))

(fn cpu-evaluator [scene plan]
  "A function from a list of points to {:distance d :color [r g b] :mirror m} for
each from the CPU evaluator (the distance is capped at the draw distance, as the
shader's); one tracer serves every batch."
  (let [T (reference.tracer scene plan)]
    (fn [points]
      (icollect [_ [x y z] (ipairs points)]
        (let [(d _ r g b m) (T.map-color x y z)]
          {:distance d :color [r g b] :mirror m})))))

(fn cpu-values [scene plan points]
  "For each point: {:distance d :color [r g b] :mirror m} from the CPU evaluator
(the distance is capped at the draw distance, as the shader's)."
  ((cpu-evaluator scene plan) points))

(fn format-line [v]
  "One output line: distance, then the material's colour and mirror amount."
  (string.format "%.9g %.6g %.6g %.6g %.6g" v.distance (. v.color 1) (. v.color 2)
                 (. v.color 3) v.mirror))

{: point-reader : parse-points : cpu-evaluator : cpu-values : format-line : max-line}
