;; `--mesh`: a scene's objects to a mesh file, for printing or another modelling
;; program. Picks what to mesh (src/mesh/scene.fnl), contours it (src/mesh/contour.fnl)
;; with a field from the CPU evaluator or the GPU (src/mesh/gpu.fnl, given by the
;; caller), colours the vertices with the scene's materials and writes STL, PLY or OBJ
;; (src/mesh/formats.fnl) through the one output writer. Progress on stderr with an
;; estimate of the time left. Pure: runs under plain LuaJIT with the CPU field.

(local contour (require :src.mesh.contour))
(local simplify (require :src.mesh.simplify))
(local mesh-scene (require :src.mesh.scene))
(local formats (require :src.mesh.formats))
(local status (require :src.util.status))
(local output (require :src.util.output))
(local min math.min)

(fn millions [n]
  (if (>= n 1e6) (string.format "%.1fM" (/ n 1e6))
      (>= n 1e3) (string.format "%.0fk" (/ n 1e3))
      (tostring n)))

(fn reporter [clock ?quiet?]
  "A progress function for contour.mesh that shows, as each phase starts and at
most twice a second within it, the phase, the share of the work done and the time
left at the rate so far."
  (let [start (clock)]
    (var last start)
    (var last-phase nil)
    ;; The estimate grows when the crossings are counted: the share shown never
    ;; goes back.
    (var shown 0)
    (fn [phase work estimate points]
      (let [now (clock)]
        (when (and (not ?quiet?) (or (not= phase last-phase) (>= (- now last) 0.5)))
          (set (last last-phase) (values now phase))
          (let [elapsed (- now start)
                left (when (and estimate (> work 0))
                       (* elapsed (/ (math.max 0 (- estimate work)) work)))]
            (status.update!
             (if left
                 (string.format "mesh: %s, %d%% (%s points), %.1f s, %s left"
                                phase
                                (do (set shown (math.max shown (math.min 99 (math.floor (/ (* 100 work) estimate)))))
                                    shown)
                                (millions points) elapsed
                                (if (< left 1) "under 1 s" (string.format "about %.0f s" left)))
                 (string.format "mesh: %s, %s points, %.1f s (finding the surface)"
                                phase (millions points) elapsed)))))))))

;; The colours' work per vertex, in field evaluations (see contour's geometry-work):
;; a material's colour (map-color, every object's material) took 9 microseconds a
;; vertex on machined-part, 11 of its distances near the surface (its guards skip
;; most objects), and about 3 of organic's.
(local colour-work 6)

(fn colour! [m field progress stats]
  ;; The material's colour at each vertex, in batches.
  (let [p m.positions
        n (/ (length p) 3)
        colors []]
    (for [start 0 (- n 1) 32768]
      (let [count (math.min 32768 (- n start))
            chunk (fcollect [q (+ 1 (* 3 start)) (* 3 (+ start count))] (. p q))
            cs (field.colors chunk count)]
        (for [q 1 (* 3 count)] (tset colors (+ (* 3 start) q) (. cs q)))
        (set stats.work (+ stats.work (* colour-work count)))
        (set stats.points (+ stats.points count))
        (progress :colours stats.work stats.estimate stats.points)))
    (set m.colors colors)
    m))

;; The simplifier's work per vertex of the grid's mesh, in field evaluations (see
;; contour's geometry-work): machined-part at 128 cells, 19,546 vertices, took 5 s
;; where its grid's mesh (266k evaluations) took 0.9.
(local adapt-work 75)

(fn adapt [m field grid error progress]
  ;; `m` simplified within `error` of the cut field's surface (--adaptive), its
  ;; stats under :adaptive. The field is the CPU evaluator's, also for a mesh made on
  ;; the GPU: the simplifier asks for a few dozen points at a time, and a GPU round
  ;; trip per collapse cost more than the evaluations (organic at 64 cells: 3.3 s
  ;; against 1.4).
  (let [counts {:points 0 :work 0}
        values-of (contour.cut-field field grid.cut counts (fn []) grid.h)
        base m.stats.work
        work (* adapt-work (/ (length m.positions) 3))
        (out stats) (simplify.simplify
                     m error grid.h (fn [flat] (values-of :simplify flat))
                     ;; Collapses end near half the triangles' count.
                     (fn [done total]
                       (progress :simplify (+ base (* work (min 1 (/ done total))))
                                 m.stats.estimate (+ m.stats.points counts.points))))]
    (set m.stats.points (+ m.stats.points counts.points))
    (set m.stats.adaptive stats)
    (set out.stats m.stats)
    out))

;; What progress raises when asked to stop (see build).
(local stopped {:stopped true})

(fn resolution-for [resolution too-many]
  ;; A resolution whose blocks fit (they grow with its square), a tenth below the
  ;; estimate and a multiple of 8 (the octree's blocks do not scale exactly).
  (math.max 8 (* 8 (math.floor (/ (* 0.9 resolution (math.sqrt (/ too-many.max-leaves too-many.leaves)))
                                  8)))))

(fn build [scene ?options]
  "Mesh `scene`. Options: :resolution (cells along the region's longest side,
default 128), :region {:lo :hi} (default the finite objects' box), :field (fn
[scene] -> a field as contour.mesh takes, with :colors; default the CPU evaluator),
:clock (seconds, for progress; default os.clock), :adaptive (a distance: edges
collapsed while every triangle stays that close to the surface, see
src/mesh/simplify.fnl), :quiet? (no progress), :stop? (a
function, true when the work is to stop: build then returns nil and :stop-message).
Returns {:mesh {:positions :triangles :colors} :message (what was left out or cut)
:grid :stats :seconds}, or nil and a message."
  (let [options (or ?options {})
        clock (or options.clock os.clock)
        make-field (or options.field mesh-scene.cpu-field)
        resolution (or options.resolution mesh-scene.default-resolution)]
    (case (mesh-scene.select-objects scene options.region)
      (nil err) (values nil err)
      selection
      (case (make-field selection.scene)
        (nil err) (values nil err)
        field
        (let [grid (doto (mesh-scene.grid-for selection resolution)
                     (tset :after-work (+ colour-work (if options.adaptive adapt-work 0))))
              start (clock)
              report (reporter clock options.quiet?)
              ;; Asked to stop (options.stop?, looked at with each batch of points):
              ;; the work is left at once, by an error this function catches.
              progress (fn [...]
                         (when (and options.stop? (options.stop?)) (error stopped))
                         (report ...))
              (ok? m) (pcall contour.mesh field grid progress)
              (coloured? cerr) (if (and ok? (< 0 (length m.triangles)))
                                   (pcall colour! m field progress m.stats)
                                   true)
              ;; --adaptive: the coloured mesh simplified (an error or a stop
              ;; counts as the colours' would).
              (m coloured? cerr) (if (and ok? coloured? options.adaptive
                                          (< 0 (length m.triangles)))
                                     (case (pcall adapt m (if options.field
                                                    (assert (mesh-scene.cpu-field selection.scene))
                                                    field)
                                        grid options.adaptive progress)
                                       (true adapted) (values adapted true)
                                       (_ e) (values m false e))
                                     (values m coloured? cerr))]
          (if (or (= m stopped) (= cerr stopped))
              (do (when (not options.quiet?) (status.done!))
                  (values nil options.stop-message))
              (and (not ok?) (= (type m) :table) m.leaves)
              ;; Too much surface for the resolution: the blocks grow with its square.
              (do (when (not options.quiet?) (status.done!))
                  (values nil (string.format
                               "the surface at %d cells fills %d blocks of 4x4x4 cells, more than the %d one mesh may have (memory follows them, up to about 3.9 GB at that many); give --resolution %d or less"
                               resolution m.leaves m.max-leaves
                               (resolution-for resolution m))))
              (not ok?) (error m 0)
              (not coloured?) (error cerr 0)
              (= 0 (length m.triangles))
              (do (when (not options.quiet?) (status.done!))
                  (values nil (.. "no surface to mesh: " selection.message
                                  (if options.region
                                      " (is the region clear of every object?)"
                                      " (every object thinner than a cell? raise --resolution)"))))
              (do (when (not options.quiet?) (status.done!))
                  {:mesh m :message selection.message : grid :stats m.stats
                   :seconds (- (clock) start)})))))))

(fn write! [m path ?options]
  "Write mesh `m` to `path` in the format its extension names. Options: :name (for
the file's header), :protect and :label as output.write! takes them. Returns true,
or nil and a message."
  (let [options (or ?options {})]
    (case (formats.format-of path)
      (nil err) (values nil err)
      format (output.write! path (formats.encode m format options.name)
                            {:protect options.protect :label options.label}))))

{: build : write!}
