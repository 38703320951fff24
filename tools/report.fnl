;; `make report`: accuracy against run time for every scene (see src/verify/report.fnl).
;;   luajit tools/fnl.lua tools/report.fnl [--quick] [--out DIR] [--scene FILE]...
;; Writes DIR/report.md, DIR/<scene>.png (gnuplot) and DIR/results.tsv; DIR is report/
;; (report/tmp/quick with --quick). Progress goes to stderr.

;; The candidate defaults, measured in the same run as the article's settings and
;; stated for the seed scene at the end of the report. Keys left out (or the whole
;; table left empty) fall back to the scene loader's defaults.
(local defaults {})   ; the loader's defaults (src/scene/load.fnl), chosen from this report

(local report (require :src.verify.report))

;; Why the defaults are what they are: written by hand from the fronts of a full run,
;; kept with the report so that the reasoning sits next to the numbers.
(local defaults-reasoning
  ["How the defaults were chosen: from the seed scene's front at 320x180 and again at"
   "640x360, the fastest settings whose error stays at or below the article's at both"
   "sizes. The hit test is the lever: a threshold relative to the distance travelled"
   "(1e-4) halves the steps per ray and, with normals and ray offsets on the same scale,"
   "lowers the error. Tetrahedron normals cost nothing over one-sided ones and are more"
   "accurate; over-relaxation 1.5 takes another tenth off. Cutting the step budget to"
   "128-200 saves little more but flips grazing rays at the horizon (hit/miss"
   "disagreements at 640x360), so the article's 500 stay. Pixel-footprint hit tests are"
   "faster still, but their larger thresholds move mirror images and shadow edges by"
   "enough to raise the error above the article's. The aim of a third of the article's"
   "time at the same error is not reached: llvmpipe runs pixels in SIMD groups that"
   "iterate until their slowest ray is done, so grazing rays set the pace; and the"
   "shadow and mirror rays, marched to the draw distance as in the article, are a large"
   "share of the frame (without reflections the seed's frame takes about 70% of the"
   "time, see the refl0 row)."
   ""
   "Re-run with the levers of issue 11 (bounds, closed-form planes and normals,"
   "out-of-steps): on the seed at 320x180 the defaults take 12.3 ms against the"
   "article's 67.0 (5.5x) at a lower error (0.71 against 1.35/255), on both fronts."
   "Around them (the seed with the defaults as its own settings) the step budget,"
   "over-relaxation and normal method no longer change the time beyond noise (0.9 steps"
   "per primary ray), a larger epsilon only adds error, and whole-scene normals or no"
   "bounds are slower and worse; so the defaults stay as they are."])

(fn parse-args [args]
  (let [out {:files []}]
    (var i 1)
    (while (<= i (length args))
      (let [a (. args i)]
        (case a
          "--quick" (set out.quick? true)
          "--out" (do (set i (+ i 1)) (set out.dir (. args i)))
          "--scene" (do (set i (+ i 1)) (table.insert out.files (. args i)))
          "--no-plots" (set out.no-plots? true)
          _ (do (io.stderr:write (.. "report: unknown argument " (tostring a) "\n"
                                     "usage: luajit tools/fnl.lua tools/report.fnl [--quick] [--out DIR] [--scene FILE]... [--no-plots]\n"))
                (os.exit 2))))
      (set i (+ i 1)))
    (when (= (length out.files) 0) (set out.files nil))
    (set out.dir (or out.dir (if out.quick? "report/tmp/quick" "report")))
    out))

(fn mkdir-p [dir]
  (let [lfs (require :lfs)]
    (var path "")
    (each [part (dir:gmatch "[^/]+")]
      (set path (if (and (= path "") (not (dir:match "^/"))) part (.. path "/" part)))
      (when (not (lfs.attributes path :mode)) (lfs.mkdir path)))))

(fn write-file [path text]
  (let [f (assert (io.open path :wb))]
    (f:write text)
    (f:close)))

(fn file-safe [name]
  (pick-values 1 (name:gsub "[^%w%-_.]" "_")))

(fn front-mark [r]
  (if (and r.pareto? r.gpu-pareto?) "cpu+gpu"
      r.pareto? "cpu"
      r.gpu-pareto? "gpu"
      ""))

(fn scene-table [s]
  (let [lines ["| front | setting | changes | ms/frame | IQR | steps/ray | cpu mean | cpu max | cpu >2/255 | cpu hit/miss | gpu mean | gpu max | gpu >2/255 | gpu hit/miss |"
               "|---|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|"]]
    (each [_ r (ipairs s.rows)]
      (let [name (.. r.name (if (> (length r.aliases) 0)
                                (.. " (= " (table.concat r.aliases ", ") ")") ""))]
        (table.insert lines
                      (string.format "| %s | %s | %s | %.1f | %.1f | %.1f | %.2f | %.0f | %.1f%% | %d/%d | %.2f | %.0f | %.1f%% | %d |"
                                     (front-mark r)
                                     (if r.pareto? (.. "**" name "**") name)
                                     (if (= r.axis :base) "scene's own"
                                         (report.describe-overrides r.overrides))
                                     r.ms r.ms-iqr r.steps r.cpu.mean r.cpu.max (* 100 r.cpu.over-share)
                                     r.cpu.hit-miss r.cpu.count
                                     r.gpu.mean r.gpu.max (* 100 r.gpu.over-share)
                                     r.gpu.hit-miss))))
    (table.concat lines "\n")))

(fn gnuplot? []
  (let [p (io.popen "command -v gnuplot 2>/dev/null")
        out (p:read :*a)]
    (p:close)
    (not= out "")))

(fn plot-scene [s dir]
  "Write DIR/<scene>.png: error against ms/frame, both error measures, fronts drawn."
  (let [png (.. dir "/" (file-safe s.name) ".png")
        data (os.tmpname)
        script (os.tmpname)
        floor-v (fn [v] (math.max v 0.01))
        lines []
        front-lines (fn [key flag]
                      (let [f (icollect [_ r (ipairs s.rows)] (when (. r flag) r))]
                        (table.sort f (fn [a b] (< a.ms b.ms)))
                        (icollect [_ r (ipairs f)]
                          (string.format "%g %g \"%s\"" (floor-v r.ms) (floor-v (. r key)) r.name))))]
    (each [_ r (ipairs s.rows)]
      (table.insert lines (string.format "%g %g %g \"%s\"" (floor-v r.ms) (floor-v r.error)
                                         (floor-v r.gpu-error)
                                         (.. r.name (if (> (length r.aliases) 0)
                                                        (.. "=" (table.concat r.aliases "="))
                                                        "")))))
    (write-file data (.. "# ms cpu-error gpu-error name\n" (table.concat lines "\n") "\n\n\n"
                         (table.concat (front-lines :error :pareto?) "\n") "\n\n\n"
                         (table.concat (front-lines :gpu-error :gpu-pareto?) "\n") "\n"))
    (write-file script
                (.. "set terminal pngcairo size 1800,900 font 'sans,10'\n"
                    "set output '" png "'\n"
                    "set multiplot layout 1,2 title '" s.name ": mean error against time per frame ("
                    s.width "x" s.height ", llvmpipe; errors below 0.01 drawn at 0.01)'\n"
                    "set logscale xy\nset grid\nset key top right\n"
                    "set xlabel 'ms per frame (median, read-back overhead subtracted)'\n"
                    "set ylabel 'mean error against the CPU reference (0-255 levels)'\n"
                    "set title 'against the converged CPU reference (sampled pixels)'\n"
                    "plot '" data "' index 0 using 1:2 with points pt 7 ps 1 lc rgb '#4060a0' title 'setting', "
                    "'' index 0 using 1:2:4 with labels offset 0.5,0.5 left font 'sans,7' tc rgb '#606060' notitle, "
                    "'' index 1 using 1:2 with linespoints lw 2 pt 6 ps 2 lc rgb '#d03020' title 'Pareto front', '' index 1 using 1:2:3 with labels offset -0.8,-0.9 right font 'sans,10:Bold' tc rgb '#d03020' notitle\n"
                    "set ylabel 'mean error against the strict GPU image (0-255 levels)'\n"
                    "set title 'against the strict GPU render (whole image)'\n"
                    "plot '" data "' index 0 using 1:3 with points pt 7 ps 1 lc rgb '#4060a0' title 'setting', "
                    "'' index 0 using 1:3:4 with labels offset 0.5,0.5 left font 'sans,7' tc rgb '#606060' notitle, "
                    "'' index 2 using 1:2 with linespoints lw 2 pt 6 ps 2 lc rgb '#d03020' title 'Pareto front', '' index 2 using 1:2:3 with labels offset -0.8,-0.9 right font 'sans,10:Bold' tc rgb '#d03020' notitle\n"
                    "unset multiplot\n"))
    (let [ok (os.execute (.. "gnuplot " script " 2>" script ".err"))
          f (io.open (.. script ".err") :rb)
          err (if f (let [t (f:read :*a)] (f:close) t) "")]
      (os.remove data)
      (os.remove script)
      (os.remove (.. script ".err"))
      (if (or (= ok 0) (= ok true)) png (values nil err)))))

(fn tsv [result]
  (let [lines ["scene\tsetting\taxis\tchanges\tms\traw_ms\tsteps\tcpu_mean\tcpu_max\tcpu_over\tcpu_hit_miss\tgpu_mean\tgpu_max\tgpu_over\tgpu_hit_miss\tfront"]]
    (each [_ s (ipairs result.scenes)]
      (each [_ r (ipairs (or s.rows []))]
        (table.insert lines (string.format "%s\t%s\t%s\t%s\t%.3f\t%.3f\t%.2f\t%.3f\t%.1f\t%.4f\t%d\t%.3f\t%.1f\t%.4f\t%d\t%s"
                                           s.name r.name r.axis (report.describe-overrides r.overrides)
                                           r.ms r.raw-ms r.steps r.cpu.mean r.cpu.max r.cpu.over-share
                                           r.cpu.hit-miss r.gpu.mean r.gpu.max r.gpu.over-share
                                           r.gpu.hit-miss (front-mark r)))))
    (.. (table.concat lines "\n") "\n")))

(fn markdown [result plots]
  (let [out ["# Accuracy against run time"
             ""
             (string.format "%s run, %s, %dx%d, %d scene(s), %.0f s. Generated by `luajit tools/fnl.lua tools/report.fnl%s`."
                            (if result.quick? "Quick" "Full") result.renderer result.width result.height
                            (length result.scenes) result.seconds (if result.quick? " --quick" ""))
             ""
             "How the columns are measured:"
             ""
             "- **ms/frame**: median wall-clock time of one frame of the scene's `:core` shaded shader through OSMesa (llvmpipe on the CPU), draw plus `glFinish` plus read-back, with the median time of an empty shader of the same size (target set-up and read-back) subtracted. The frames of all settings of a scene are interleaved round by round, so a change of machine load falls on every setting alike. **IQR** is the interquartile range of those frame times: differences in ms/frame smaller than it are noise (llvmpipe runs on the machine's CPU cores, shared with anything else running)."
             "- **steps/ray**: mean primary-ray steps over the whole image, decoded exactly from the GPU heat view (`steps / max-steps` as colour) rendered to a float target."
             (.. "- **cpu ...**: the GPU image against the CPU reference marcher (double precision) at converged settings, on sampled pixels (`compare.sample-pixels`: a jittered grid and pixels beside silhouettes, shadow and reflected edges). Error per pixel is the largest channel difference in 0-255 levels; *mean*, *max*, and the share of pixels over "
                 report.tolerance "/255.")
             "- **cpu hit/miss**: sampled pixels where the primary ray's hit differs between the GPU at the tested settings and the reference. The GPU's hit comes from its normals view at the same settings (black exactly where the ray misses: a unit normal never maps to black), so it is the tested shader's own march, not a CPU imitation of it."
             "- **gpu ...**: the same measures over every pixel against the GPU at the strictest settings (which shows float32 effects the CPU reference does not have); **gpu hit/miss** compares the two normals views pixel by pixel."
             "- **front**: on the Pareto front of (ms/frame, mean error) against the CPU reference (`cpu`, setting in bold) or against the strict GPU image (`gpu`). Rows with equal settings are measured once; `(= name)` lists the duplicates."
             ""]]
    (each [_ s (ipairs result.scenes)]
      (table.insert out (.. "## " s.name " (" s.file ")"))
      (table.insert out "")
      (if s.error
          (table.insert out (.. "Not measured: " s.error))
          (do
            (table.insert out (string.format "Scene settings: %s. Converged CPU reference: %s, on %d pixels. Strict GPU: %s. %d timing rounds; empty-shader overhead %.1f ms/frame."
                                             (report.describe-overrides (. (report.find-row s "base") :render))
                                             (report.describe-overrides s.cpu-render) s.pixel-count
                                             (report.describe-overrides s.gpu-render)
                                             s.rounds s.overhead-ms))
            (table.insert out "")
            (table.insert out (scene-table s))
            (table.insert out "")
            (let [png (. plots s.name)]
              (if png
                  (table.insert out (.. "![" s.name ": error against time](" (png:match "([^/]+)$") ")"))
                  (table.insert out "(no plot: gnuplot is not available or failed)")))
            (table.insert out "")
            (each [_ line (ipairs (report.reading s))]
              (table.insert out (.. "- " line)))
            (when (> (length s.skipped) 0)
              (table.insert out "")
              (table.insert out "Not measured:")
              (table.insert out "")
              (each [_ k (ipairs s.skipped)]
                (table.insert out (.. "- " k.name " (" (report.describe-overrides k.overrides) "): " k.reason))))))
      (table.insert out ""))
    (table.insert out "## Summary")
    (table.insert out "")
    (table.insert out (report.summary result))
    (table.insert out "")
    (table.insert out "## Article settings against the defaults")
    (table.insert out "")
    (table.insert out (or (report.defaults-statement result "seed")
                          (let [(_ why) (report.defaults-statement result "seed")] why)))
    (table.insert out "")
    (each [_ line (ipairs defaults-reasoning)] (table.insert out line))
    (table.insert out "")
    (table.concat out "\n")))

(let [args (parse-args [...])
      (result why) (report.run {:quick? args.quick? :files args.files :defaults defaults})]
  (when (not result)
    (io.stderr:write (.. "report: cannot render headless: " (tostring why) "\n"))
    (os.exit 1))
  (mkdir-p args.dir)
  (let [plots {}
        can-plot? (and (not args.no-plots?) (gnuplot?))]
    (when (and (not can-plot?) (not args.no-plots?))
      (io.stderr:write "report: gnuplot not found; no plots (apt-get install gnuplot-nox)\n"))
    (when can-plot?
      (each [_ s (ipairs result.scenes)]
        (when (and s.rows (> (length s.rows) 0))
          (case (plot-scene s args.dir)
            png (tset plots s.name png)
            (nil err) (io.stderr:write (.. "report: plot for " s.name " failed: " err "\n"))))))
    (write-file (.. args.dir "/report.md") (markdown result plots))
    (write-file (.. args.dir "/results.tsv") (tsv result))
    (io.stderr:write (string.format "report: wrote %s/report.md in %.0f s\n" args.dir result.seconds))
    (case (report.defaults-statement result "seed")
      text (io.stderr:write (.. text "\n")))))
