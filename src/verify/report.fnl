;; Accuracy against run time (`make report`): every scene in scenes/ and scenes/stress/
;; rendered headless through OSMesa at a sweep of render settings (one axis at a time
;; around the scene's own settings, plus combined candidates). For each setting:
;;   ms/frame    median wall-clock time of the :core shaded shader, frames interleaved
;;               with the other settings of the scene; the time of an empty shader of
;;               the same size (target set-up, glFinish, read-back) is subtracted
;;   steps       mean primary-ray steps, read from the GPU heat view on a float target
;;               (steps / max-steps is decoded from the heat colours exactly)
;;   cpu error   against the CPU reference (double precision) at converged settings, on
;;               sampled pixels (compare.sample-pixels: jittered grid plus edge pixels)
;;   gpu error   against the GPU at the strictest settings, over the whole image
;;   hit/miss    disagreements of the primary ray's hit, from the GPU normals view
;;               (black exactly on a miss) against the reference's :hit? (sampled
;;               pixels) and against the strict GPU normals view (whole image)
;; and per scene the Pareto front in (ms/frame, error). Pure LuaJIT: no LÖVE.

;; `pairs` under another name: a loop over `pairs` by that name is LuaJIT's ITERN,
;; which Debian 12's LuaJIT ends early once despecialised (see src/util/wire.fnl).
(local each-pair pairs)

(local ffi (require :ffi))
(local fennel (require :fennel))
(local scene-loader (require :src.scene.load))
(local plan-mod (require :src.render.plan))
(local camera (require :src.render.camera))
(local codegen (require :src.render.codegen))
(local uniforms (require :src.render.uniforms))
(local headless (require :src.backend.headless))
(local reference (require :src.reference))
(local compare (require :src.verify.compare))
(local filestat (require :src.util.filestat))

;;; Settings

;; The article's settings. A key the scene loader does not know yet is the renderer's
;; built-in behaviour, which is the article's: a setting that asks for the article's
;; value of an unknown key still applies (without it); any other value is skipped.
(local article {:max-steps 500 :epsilon 1e-4 :hit-test :fixed :normals :one-sided
                :relaxation 1 :normals-of :scene :bounds false :out-of-steps :surface})

;; The settings a "defaults" table may leave out are filled from the loader's defaults.
(local tuning-keys [:max-steps :epsilon :hit-test :normals :relaxation :normals-of :bounds
                    :out-of-steps])

;; Converged settings, with a fallback for when the loader lacks the newer keys.
(local strict-cpu [{:max-steps 4000 :hit-test :pixel :epsilon 0.02 :normals :central
                    :relaxation 1}
                   {:max-steps 4000 :epsilon 1e-5}])
(local strict-gpu [{:max-steps 4000 :hit-test :pixel :epsilon 0.05 :normals :central
                    :relaxation 1}
                   {:max-steps 4000 :epsilon 1e-4}])

;; A pixel counts as wrong above this many 0..255 levels in some channel.
(local tolerance 2)

(local configs
  {:full {:width 320 :height 180 :rounds-min 5 :rounds-max 15 :timing-budget-ms 40000
          :sample {:grid 16 :extra 256 :step 4 :seed 1} :max-scenes nil}
   :quick {:width 160 :height 90 :rounds-min 3 :rounds-max 3 :timing-budget-ms 4000
           :sample {:grid 10 :extra 60 :step 4 :seed 1} :max-scenes 1}})

(fn fmt-number [v]
  (if (= (type v) :number)
      (if (= v (math.floor v)) (string.format "%d" v) (string.format "%g" v))
      (tostring v)))

(fn short-eps [e]
  ;; 0.001 -> "1e-3", 0.5 -> "0.5"
  (if (and (< e 0.01) (> e 0))
      (let [ex (math.floor (+ (/ (math.log e) (math.log 10)) 1e-6))
            m (/ e (^ 10 ex))]
        (if (< (math.abs (- m (math.floor (+ m 0.5)))) 1e-9)
            (.. (string.format "%d" (math.floor (+ m 0.5))) "e" ex)
            (string.format "%g" e)))
      (string.format "%g" e)))

(fn describe-overrides [overrides]
  "`{:max-steps 64 :normals :tetrahedron}` -> \"max-steps 64, normals tetrahedron\"."
  (let [keys (doto (icollect [k (each-pair overrides)] k) table.sort)]
    (if (= (length keys) 0) "the scene's own settings"
        (table.concat (icollect [_ k (ipairs keys)]
                        (.. k " " (fmt-number (. overrides k))))
                      ", "))))

(fn setting [name axis overrides ?note]
  {: name : axis : overrides :note ?note})

(fn sweep-settings [base quick?]
  "The settings to measure for a scene whose own render section is `base`: a list of
{:name :axis :overrides}. :axis is :base, :reference, an axis name or :combined."
  (let [out [(setting "base" :base {})
             (setting "article" :reference article)]
        add (fn [name axis overrides] (table.insert out (setting name axis overrides)))
        eps (or base.epsilon 1e-4)
        hit (or base.hit-test :fixed)]
    (if quick?
        (do (add "ms64" :max-steps {:max-steps 64})
            (add "px0.5" :hit-test {:hit-test :pixel :epsilon 0.5})
            (add "tetra" :normals {:normals :tetrahedron})
            (add "w1.4" :relaxation {:relaxation 1.4})
            (add "px.5+tet+w1.4+ms128" :combined {:hit-test :pixel :epsilon 0.5
                                                   :normals :tetrahedron :relaxation 1.4
                                                   :max-steps 128}))
        (do
          (each [_ n (ipairs [32 64 128 256 1000])]
            (when (not= n base.max-steps) (add (.. "ms" n) :max-steps {:max-steps n})))
          (each [_ k (ipairs [0.1 10 100 1000])]
            (let [e (* eps k)]
              (add (.. (if (= hit :fixed) "eps" (.. (tostring hit) "-eps")) (short-eps e))
                   :epsilon {:epsilon e})))
          (each [_ e (ipairs [1e-4 1e-3 1e-2])]
            (add (.. "rel" (short-eps e)) :hit-test {:hit-test :relative :epsilon e}))
          (each [_ e (ipairs [0.1 0.25 0.5 1])]
            (add (.. "px" e) :hit-test {:hit-test :pixel :epsilon e}))
          (add "central" :normals {:normals :central})
          (add "tetra" :normals {:normals :tetrahedron})
          ;; The levers of issue 11 and the normals of issue 10, each against the
          ;; scene's own.
          (each [_ of (ipairs [:object :scene])]
            (when (not= of base.normals-of)
              (add (.. "normals-of-" of) :normals {:normals-of of})))
          (each [_ b (ipairs [true false])]
            (when (not= b base.bounds)
              (add (if b "bounds" "no-bounds") :bounds {:bounds b})))
          (each [_ o (ipairs [:background :surface])]
            (when (not= o base.out-of-steps)
              (add (.. "oos-" o) :out-of-steps {:out-of-steps o})))
          (each [_ w (ipairs [1.2 1.4 1.6 1.8])]
            (add (.. "w" w) :relaxation {:relaxation w}))
          (for [r 0 (- (or base.reflections 0) 1)]
            (add (.. "refl" r) :reflections {:reflections r}))
          (let [px {:hit-test :pixel :epsilon 0.5 :normals :tetrahedron}
                with (fn [extra]
                       (let [out (collect [k v (each-pair px)] k v)]
                         (each [k v (each-pair extra)] (tset out k v))
                         out))]
            (add "px.5+tet" :combined px)
            (each [_ w (ipairs [1.2 1.4 1.6])]
              (add (.. "px.5+tet+w" w) :combined (with {:relaxation w})))
            (each [_ n (ipairs [64 128 256])]
              (add (.. "px.5+tet+w1.4+ms" n) :combined (with {:relaxation 1.4 :max-steps n})))
            (add "px.25+tet+w1.4+ms128" :combined (with {:epsilon 0.25 :relaxation 1.4
                                                         :max-steps 128}))
            (add "px1+tet+w1.4+ms128" :combined (with {:epsilon 1 :relaxation 1.4
                                                       :max-steps 128}))
            (add "rel1e-3+tet+w1.4" :combined {:hit-test :relative :epsilon 1e-3
                                               :normals :tetrahedron :relaxation 1.4})
            ;; Relative hit tests keep secondary rays close to the surface; with
            ;; relaxation and a smaller step budget they are the candidates for new
            ;; defaults (grazing rays that run out of steps still count as hits).
            (each [_ e (ipairs [1e-4 2e-4 3e-4])]
              (each [_ n (ipairs [128 200 500])]
                (add (.. "rel" (short-eps e) "+tet+w1.5+ms" n) :combined
                     {:hit-test :relative :epsilon e :normals :tetrahedron
                      :relaxation 1.5 :max-steps n})))
            (add "rel1e-4+tet+w1.8+ms200" :combined {:hit-test :relative :epsilon 1e-4
                                                     :normals :tetrahedron :relaxation 1.8
                                                     :max-steps 200})
            (add "px0.1+tet+w1.5+ms128" :combined {:hit-test :pixel :epsilon 0.1
                                                   :normals :tetrahedron :relaxation 1.5
                                                   :max-steps 128}))))
    out))

(fn known-render-keys []
  (collect [k (each-pair (. (scene-loader.defaults) :render))] k true))

(fn defaults-overrides [?defaults]
  "The overrides of the \"defaults\" setting: `?defaults` (a partial render table)
with the tuning keys it leaves out taken from the scene loader's defaults."
  (let [loader (. (scene-loader.defaults) :render)
        given (or ?defaults {})
        out (collect [k v (each-pair given)] k v)]
    (each [_ k (ipairs tuning-keys)]
      (when (and (= nil (. out k)) (not= nil (. loader k)))
        (tset out k (. loader k))))
    out))

(fn validate-render [render]
  "nil when `render` is a valid render section for the loader, else its message."
  (let [source (.. "{:objects [] :render " (fennel.view render {:one-line? true}) "}")
        (ok? err) (scene-loader.load-string source "settings")]
    (when (not ok?) err)))

(fn apply-setting [base overrides known]
  "The render section `base` with `overrides` applied: the table, or nil and why the
setting cannot be measured with the loader as it is."
  (let [out (collect [k v (each-pair base)] k v)]
    (var why nil)
    (each [k v (each-pair overrides)]
      (if (. known k) (tset out k v)
          (= v (. article k)) nil
          (set why (.. "the scene format has no :" k " yet"))))
    (if why (values nil why)
        (case (validate-render out)
          nil out
          err (values nil err)))))

(fn first-available [specs base known]
  (var found nil)
  (var chosen nil)
  (var why nil)
  (each [_ spec (ipairs specs) &until found]
    (case (apply-setting base spec known)
      r (do (set found r) (set chosen spec))
      (nil err) (set why err)))
  (values found (or chosen why)))

(fn render-key [render]
  (fennel.view render {:one-line? true}))

(fn with-render [s render]
  (doto (collect [k v (each-pair s)] k v) (tset :render render)))

;;; Pareto front

(fn pareto-front [rows ?time-key ?error-key]
  "Indices (ascending) of the rows not dominated in (time, error): no other row is at
least as fast and at least as accurate and strictly better in one of them. Rows whose
time or error is nil are left out. Keys default to :ms and :error."
  (let [tk (or ?time-key :ms)
        ek (or ?error-key :error)
        usable (fn [r] (and (= (type (. r tk)) :number) (= (type (. r ek)) :number)))
        out []]
    (each [i a (ipairs rows)]
      (when (usable a)
        (var dominated? false)
        (each [j b (ipairs rows) &until dominated?]
          (when (and (not= i j) (usable b)
                     (<= (. b tk) (. a tk)) (<= (. b ek) (. a ek))
                     (or (< (. b tk) (. a tk)) (< (. b ek) (. a ek))))
            (set dominated? true)))
        (when (not dominated?) (table.insert out i))))
    out))

;;; Measurement helpers

(fn now-ms []
  "Monotonic wall-clock time in milliseconds (one declaration of clock_gettime for
the whole program: src/util/filestat.fnl's)."
  (* 1000 (filestat.monotonic)))

(local {: median} (require :src.util.stats))

(fn iqr [xs]
  "Interquartile range of the numbers `xs` (nearest-rank quartiles): the timing noise."
  (let [s (icollect [_ x (ipairs xs)] x)
        n (length s)]
    (table.sort s)
    (if (= n 0) 0
        (- (. s (math.max 1 (math.ceil (* 0.75 n)))) (. s (math.max 1 (math.ceil (* 0.25 n))))))))

(fn heat->fraction [r g b]
  "Inverse of the heat view's colour map (reference.heat-color): steps / max-steps."
  (if (and (<= r 0) (<= g 0)) (/ (- b 0.5) 4)
      (<= r 0) (/ (+ g 0.5) 4)
      (> b 0) (/ (+ r 1.5) 4)
      (> g 0) (/ (- 3.5 g) 4)
      (/ (- 4.5 r) 4)))

(local empty-shader "#version 330 core
out vec4 fragColor;
void main() {
    fragColor = vec4(0.0, 0.0, 0.0, 1.0);
}
")

(fn compile-cached [ctx cache source]
  (when (= nil (. cache source))
    (let [(program err) (headless.compile ctx source)]
      (tset cache source (or program {:error err}))))
  (let [p (. cache source)]
    (if (= (type p) :number) p (values nil p.error))))

(fn release-all [ctx cache]
  (each [_ p (each-pair cache)]
    (when (= (type p) :number) (headless.release ctx p))))

(fn hit-mask [image]
  "A byte per pixel: 1 where the normals view is not black (the primary ray hit)."
  (let [n (* image.width image.height)
        mask (ffi.new "uint8_t[?]" n)
        p image.pixels]
    (for [i 0 (- n 1)]
      (let [j (* 4 i)]
        (tset mask i (if (> (+ (. p j) (. p (+ j 1)) (. p (+ j 2))) 0) 1 0))))
    mask))

(fn mean-steps [image max-steps]
  (let [n (* image.width image.height)
        p image.pixels]
    (var sum 0)
    (for [i 0 (- n 1)]
      (let [j (* 4 i)]
        (set sum (+ sum (heat->fraction (. p j) (. p (+ j 1)) (. p (+ j 2)))))))
    (* max-steps (/ sum n))))

(fn image-error [a b]
  "Per-pixel largest channel difference (0..255) of two RGBA8 images of one size:
{:mean :max :over-share (fraction of pixels above `tolerance`) :count}."
  (let [n (* a.width a.height)
        pa a.pixels pb b.pixels]
    (var sum 0)
    (var biggest 0)
    (var over 0)
    (for [i 0 (- n 1)]
      (let [j (* 4 i)
            d (math.max (math.abs (- (. pa j) (. pb j)))
                        (math.abs (- (. pa (+ j 1)) (. pb (+ j 1))))
                        (math.abs (- (. pa (+ j 2)) (. pb (+ j 2)))))]
        (set sum (+ sum d))
        (when (> d biggest) (set biggest d))
        (when (> d tolerance) (set over (+ over 1)))))
    {:mean (/ sum n) :max biggest :over-share (/ over n) :count n}))

(fn mask-disagreements [a b n]
  (var count 0)
  (for [i 0 (- n 1)]
    (when (not= (. a i) (. b i)) (set count (+ count 1))))
  count)

(fn reference-error [expected image mask]
  "Error of the RGBA8 `image` against reference results `expected` (sampled pixels),
and hit/miss disagreements of `mask` with the reference's :hit?."
  (let [diffs []]
    (var misses 0)
    (each [_ r (ipairs expected)]
      (let [(gr gg gb) (headless.pixel image r.x r.y)
            cpu (icollect [_ c (ipairs r.color)] (* 255 c))]
        (table.insert diffs (compare.pixel-diff [gr gg gb] cpu))
        (when (not= (= 1 (. mask (+ r.x (* r.y image.width)))) (not (not r.hit?)))
          (set misses (+ misses 1)))))
    (let [st (compare.stats diffs tolerance)]
      {:mean st.mean :max st.max :over-share (/ st.over (math.max 1 st.count))
       :count st.count :hit-miss misses})))

;;; Per scene

(fn list-scenes [?dirs]
  "Scene files in scenes/ and scenes/stress/ (listed now; a missing folder is skipped)."
  (let [lfs (require :lfs)
        out []]
    (each [_ dir (ipairs (or ?dirs ["scenes" "scenes/stress"]))]
      (when (= :directory (lfs.attributes dir :mode))
        (let [files (icollect [name (lfs.dir dir)]
                      (when (name:match "%.fnl$") (.. dir "/" name)))]
          (table.sort files)
          (each [_ f (ipairs files)] (table.insert out f)))))
    out))

(fn progress [options fmt ...]
  (when (not= false options.progress?)
    (io.stderr:write (.. (string.format "[%6.1fs] " (/ (- (now-ms) options.started) 1000))
                         (string.format fmt ...) "\n"))
    (io.stderr:flush)))

(fn gpu-pass [ctx cache s w h cam view ?float?]
  "Compile and render `s` once in `view`: the image and the program, or nil + error."
  (case (plan-mod.scene->plan s {: view})
    (nil err) (values nil err)
    p (case (case (codegen.shader p :core)
              source (compile-cached ctx cache source)
              (nil err) (values nil err))
        (nil err) (values nil err)
        program (let [us (uniforms.pack s p cam w h)]
                  (case (headless.render ctx program {:width w :height h :uniforms us
                                                      :float? ?float?})
                    (nil err) (values nil err)
                    image (values image program us))))))

(fn measure-scene [ctx file index total options]
  "Sweep the settings for the scene `file`: {:name :file :rows [...] :skipped [...]
:overhead-ms ...} or {:name :file :error message}."
  (let [{: width : height} options
        w width h height
        (s err) (scene-loader.load-file file)]
    (if (not s)
        {:file file :name file :error err}
        (let [known (known-render-keys)
              base s.render
              cam (camera.from-scene s)
              cache {}
              settings (sweep-settings base options.quick?)
              rows []
              skipped []
              seen {}
              result {:file file :name s.name : rows : skipped :width w :height h}]
          (table.insert settings (setting "defaults" :reference
                                          (defaults-overrides options.defaults)))
          ;; Converged references.
          (let [(cpu-render cpu-spec) (first-available strict-cpu base known)
                (gpu-render gpu-spec) (first-available strict-gpu base known)]
            (if (or (not cpu-render) (not gpu-render))
                (set result.error (.. "no converged settings: " (tostring (if cpu-render gpu-spec cpu-spec))))
                (let [cpu-scene (with-render s cpu-render)
                      base-plan (assert (plan-mod.scene->plan s))
                      cpu-plan (assert (plan-mod.scene->plan cpu-scene))
                      t0 (now-ms)
                      pixels (compare.sample-pixels s base-plan cam w h options.sample)
                      expected (reference.render-pixels cpu-scene cpu-plan cam w h pixels)
                      gpu-scene (with-render s gpu-render)
                      strict-image (gpu-pass ctx cache gpu-scene w h cam :shaded)
                      strict-normals (gpu-pass ctx cache gpu-scene w h cam :normals)]
                  (progress options "scene %d/%d %s: reference on %d pixels in %.1f s"
                            index total s.name (length pixels) (/ (- (now-ms) t0) 1000))
                  (set result.cpu-render cpu-spec)
                  (set result.gpu-render gpu-spec)
                  (set result.pixel-count (length pixels))
                  (if (not (and strict-image strict-normals))
                      (set result.error "the strict GPU render failed")
                      (let [strict-mask (hit-mask strict-normals)
                            n (length settings)]
                        (table.insert settings (setting "strict" :reference gpu-spec))
                        ;; Accuracy: one render per setting and view.
                        (each [j st (ipairs settings)]
                          (progress options "scene %d/%d %s: setting %d/%d %s"
                                    index total s.name j (+ n 1) st.name)
                          (case (apply-setting base st.overrides known)
                            (nil why) (table.insert skipped {:name st.name :axis st.axis
                                                             :overrides st.overrides
                                                             :reason why})
                            render
                            (let [key (render-key render)
                                  same (. seen key)]
                              (if same
                                  (table.insert same.aliases st.name)
                                  (let [ts (with-render s render)
                                        (image program us) (gpu-pass ctx cache ts w h cam :shaded)
                                        normals (and image (gpu-pass ctx cache ts w h cam :normals))
                                        heat (and normals (gpu-pass ctx cache ts w h cam :heat true))]
                                    (if (not heat)
                                        (table.insert skipped {:name st.name :axis st.axis
                                                               :overrides st.overrides
                                                               :reason (.. "render failed: "
                                                                           (tostring (or program us)))})
                                        (let [mask (hit-mask normals)
                                              cpu (reference-error expected image mask)
                                              gpu (image-error image strict-image)
                                              row {:name st.name :axis st.axis
                                                   :overrides st.overrides :render render
                                                   :aliases [] : program :uniforms us
                                                   :steps (mean-steps heat render.max-steps)
                                                   : cpu :gpu gpu
                                                   :error cpu.mean :gpu-error gpu.mean
                                                   :times []}]
                                          (set gpu.hit-miss (mask-disagreements
                                                             mask strict-mask (* w h)))
                                          (tset seen key row)
                                          (table.insert rows row))))))))
                        ;; Timing: rounds over every setting and the empty shader, so a
                        ;; change of machine load falls on all of them alike.
                        (let [empty (assert (compile-cached ctx cache empty-shader))
                              time! (fn [program us]
                                      (let [t (now-ms)]
                                        (assert (headless.render ctx program
                                                                 {:width w :height h :uniforms us}))
                                        (- (now-ms) t)))
                              empty-times []
                              t-first (now-ms)]
                          ;; Warm-up round, which also sizes the number of rounds.
                          (time! empty [])
                          (each [_ row (ipairs rows)] (time! row.program row.uniforms))
                          (let [round-ms (math.max 1 (- (now-ms) t-first))
                                rounds (math.max options.rounds-min
                                                 (math.min options.rounds-max
                                                           (math.floor (/ options.timing-budget-ms
                                                                          round-ms))))]
                            (for [r 1 rounds]
                              (progress options "scene %d/%d %s: timing round %d/%d (%d settings)"
                                        index total s.name r rounds (length rows))
                              (table.insert empty-times (time! empty []))
                              (each [_ row (ipairs rows)]
                                (table.insert row.times (time! row.program row.uniforms))))
                            (set result.rounds rounds))
                          (set result.overhead-ms (median empty-times))
                          (each [_ row (ipairs rows)]
                            (set row.raw-ms (median row.times))
                            (set row.ms-iqr (iqr row.times))
                            (set row.ms (math.max 0 (- row.raw-ms result.overhead-ms)))
                            (set row.program nil)
                            (set row.uniforms nil)))
                        ;; Fronts.
                        (each [_ i (ipairs (pareto-front rows :ms :error))]
                          (tset (. rows i) :pareto? true))
                        (each [_ i (ipairs (pareto-front rows :ms :gpu-error))]
                          (tset (. rows i) :gpu-pareto? true)))))))
          (release-all ctx cache)
          (collectgarbage)
          result))))

(fn run [?options]
  "Measure every scene. Options: :quick? (small run), :files (scene files; default
scenes/ and scenes/stress/), :defaults (a partial render table, see
defaults-overrides), :progress? (default true; progress lines on stderr), :width
:height. Returns {:scenes [per-scene results] :config :renderer :seconds}, or nil and
a reason when OSMesa is not available."
  (let [options (collect [k v (each-pair (or ?options {}))] k v)
        config (. configs (if options.quick? :quick :full))]
    (each [k v (each-pair config)]
      (when (= nil (. options k)) (tset options k v)))
    (set options.started (now-ms))
    (case (headless.context)
      (nil why) (values nil why)
      ctx
      (let [files (or options.files
                      (let [all (list-scenes)]
                        (if options.max-scenes
                            ;; The quick run keeps the seed scene when there is one.
                            (let [seed (icollect [_ f (ipairs all)]
                                         (when (f:match "/seed%.fnl$") f))]
                              (if (> (length seed) 0) seed
                                  (icollect [i f (ipairs all)]
                                    (when (<= i options.max-scenes) f))))
                            all)))
            scenes (icollect [i f (ipairs files)]
                     (measure-scene ctx f i (length files) options))]
        {: scenes
         :quick? (not (not options.quick?))
         :width options.width :height options.height
         :defaults (defaults-overrides options.defaults)
         :renderer (. (headless.limits ctx) :renderer)
         :seconds (/ (- (now-ms) options.started) 1000)}))))

;;; Reading the results

(fn find-row [scene-result name]
  (var found nil)
  (each [_ r (ipairs (or scene-result.rows [])) &until found]
    (when (or (= r.name name)
              (accumulate [hit false _ a (ipairs r.aliases)] (or hit (= a name))))
      (set found r)))
  found)

(fn find-scene [result name]
  (var found nil)
  (each [_ s (ipairs result.scenes) &until found]
    (when (= s.name name) (set found s)))
  found)

(fn row-summary [r]
  (string.format "%.1f ms/frame, mean error %.2f/255 (max %.0f, %.1f%% of pixels over %d/255, %d hit/miss) against the CPU reference, %.2f/255 against the strict GPU image, %.1f steps per ray"
                 r.ms r.cpu.mean r.cpu.max (* 100 r.cpu.over-share) tolerance r.cpu.hit-miss
                 r.gpu.mean r.steps))

(fn defaults-statement [result ?scene-name]
  "Error and ms/frame of the article's settings and of the \"defaults\" setting for
the seed scene (or `?scene-name`), measured in the same run: a sentence, and
{:article row :defaults row :speedup} (nil and a reason when not measured)."
  (let [name (or ?scene-name "seed")
        s (find-scene result name)
        a (and s (find-row s "article"))
        d (and s (find-row s "defaults"))]
    (if (not (and a d))
        (values nil (.. "scene " name " has no measured article and defaults rows"))
        (let [speedup (if (> d.ms 0) (/ a.ms d.ms) math.huge)
              same? (= a d)]
          (values
            (.. "Scene " name ", " s.width "x" s.height ": the article's settings ("
                (describe-overrides article) ") take " (row-summary a) ". "
                (if same?
                    "The defaults are the same settings."
                    (.. "The defaults (" (describe-overrides result.defaults)
                        ") take " (row-summary d) ": "
                        (string.format "%.2fx the article's speed" speedup)
                        (string.format ", mean error %s by %.2f/255."
                                       (if (<= d.cpu.mean a.cpu.mean) "lower" "higher")
                                       (math.abs (- d.cpu.mean a.cpu.mean))))))
            {:article a :defaults d : speedup})))))

(fn axis-sentence [scene-result axis label]
  (let [base (find-row scene-result "base")
        rows (icollect [_ r (ipairs scene-result.rows)] (when (= r.axis axis) r))]
    (when (and base (> (length rows) 0))
      (.. label ": "
          (table.concat
            (icollect [_ r (ipairs rows)]
              (string.format "%s %.1f ms (%+.0f%%), error %.2f"
                             r.name r.ms (if (> base.ms 0) (* 100 (- (/ r.ms base.ms) 1)) 0)
                             r.error))
            "; ")
          "."))))

(fn reading [scene-result]
  "Sentences on one scene's measured numbers."
  (let [rows scene-result.rows
        front (icollect [_ r (ipairs rows)] (when r.pareto? r))
        base (find-row scene-result "base")
        art (find-row scene-result "article")
        out []]
    (table.sort front (fn [a b] (< a.ms b.ms)))
    (when (> (length front) 0)
      (let [fast (. front 1)
            exact (. front (length front))]
        (table.insert out
                      (string.format "The Pareto front (ms/frame against mean error to the CPU reference) has %d of %d settings: %s. The fastest, %s, takes %.1f ms at error %.2f; the most accurate, %s, takes %.1f ms at error %.2f."
                                     (length front) (length rows)
                                     (table.concat (icollect [_ r (ipairs front)] r.name) ", ")
                                     fast.name fast.ms fast.error exact.name exact.ms exact.error))))
    (when art
      (let [dominators (icollect [_ r (ipairs rows)]
                         (when (and (not= r art) (<= r.ms art.ms) (<= r.error art.error)) r))]
        (table.sort dominators (fn [a b] (< a.ms b.ms)))
        (table.insert out
                      (if (= (length dominators) 0)
                          (string.format "The article's settings (%.1f ms, error %.2f) are on the front." art.ms art.error)
                          (let [d (. dominators 1)]
                            (string.format "The article's settings (%.1f ms, error %.2f) are dominated by %d settings; the fastest of them, %s, takes %.1f ms (%.1fx faster) at error %.2f."
                                           art.ms art.error (length dominators) d.name d.ms
                                           (if (> d.ms 0) (/ art.ms d.ms) math.huge) d.error))))
        ;; The fastest setting within half a level of the article's error.
        (let [near (icollect [_ r (ipairs rows)] (when (<= r.error (+ art.error 0.5)) r))]
          (table.sort near (fn [a b] (< a.ms b.ms)))
          (let [k (. near 1)]
            (when (and k (not= k art))
              (table.insert out (string.format "Within 0.5/255 of the article's mean error the fastest setting is %s: %.1f ms against %.1f (%.1fx), error %.2f, %.1f steps per ray against %.1f."
                                               k.name k.ms art.ms
                                               (if (> k.ms 0) (/ art.ms k.ms) math.huge)
                                               k.error k.steps art.steps)))))))
    (each [_ [axis label] (ipairs [[:max-steps "Max steps"] [:epsilon "Epsilon"]
                                   [:hit-test "Hit test"] [:normals "Normals"]
                                   [:relaxation "Relaxation"] [:reflections "Reflections"]
                                   [:combined "Combined"]])]
      (let [s (axis-sentence scene-result axis label)]
        (when s (table.insert out s))))
    (when (and base (> (length scene-result.skipped) 0))
      (table.insert out (.. (length scene-result.skipped) " settings could not be measured: "
                            (table.concat (icollect [_ k (ipairs scene-result.skipped)] k.name) ", ")
                            " (see below).")))
    out))

(fn summary [result]
  "A paragraph over all scenes: which settings are on the Pareto front how often."
  (let [counts {}
        measured (icollect [_ s (ipairs result.scenes)] (when (and s.rows (> (length s.rows) 0)) s))]
    (each [_ s (ipairs measured)]
      (each [_ r (ipairs s.rows)]
        (when r.pareto?
          (tset counts r.name (+ 1 (or (. counts r.name) 0))))))
    (let [names (doto (icollect [k (each-pair counts)] k)
                  (table.sort (fn [a b] (if (= (. counts a) (. counts b)) (< a b)
                                            (> (. counts a) (. counts b))))))
          n (length measured)
          everywhere (icollect [_ k (ipairs names)] (when (= (. counts k) n) k))
          speedups (icollect [_ s (ipairs measured)]
                     (let [art (find-row s "article")]
                       (when art
                         (let [near (icollect [_ r (ipairs s.rows)]
                                      (when (<= r.error (+ art.error 0.5)) r))]
                           (table.sort near (fn [a b] (< a.ms b.ms)))
                           (let [k (. near 1)]
                             (string.format "%s %s (%.1fx)" s.name k.name
                                            (if (> k.ms 0) (/ art.ms k.ms) math.huge)))))))]
      (.. "Over " n " scene" (if (= n 1) "" "s") " the settings most often on the Pareto front are "
          (table.concat (icollect [i k (ipairs names) &until (> i 8)]
                          (.. k " (" (. counts k) "/" n ")"))
              ", ")
          ". "
          (if (> (length everywhere) 0)
              (.. "On the front in every scene: " (table.concat everywhere ", ") ". ")
              "No setting is on the front in every scene. ")
          "The fastest setting within 0.5/255 of the article's mean error, per scene: "
          (table.concat speedups "; ") "."))))

{: pareto-front : iqr : sweep-settings : apply-setting : defaults-overrides : heat->fraction
 : list-scenes : run : measure-scene : defaults-statement : reading : summary
 : describe-overrides : find-row : find-scene : median : article : tuning-keys
 : strict-cpu : strict-gpu : tolerance : configs}
