;; Golden images: every scene in scenes/ rendered by the real app (LÖVE on Mesa, through
;; `love . --render`) at a fixed size, compared with the PNG kept in test/golden/ under a
;; fuzzy budget per scene. Shared by the golden spec and `make golden`.

(local png (require :src.util.png))

(local size [256 224])
(local golden-dir "test/golden")
(local out-dir "test/out")

;; Per-pixel tolerance: piglit's probe tolerance, 2/255 per channel, covers rounding
;; of the float colour to 8 bits.
(local channel-tolerance 2)

;; Pixels allowed over the tolerance, per scene, and the largest channel difference
;; allowed among them. The goldens were rendered on this project's CI machine kind
;; (Mesa 22.3 llvmpipe) and re-rendering there gives identical images (0 pixels over);
;; llvmpipe's float results still depend on the CPU's vector width, and a changed
;; rounding flips a grazing ray or a shadow-acne speck on the ground plane, each a
;; single pixel at most a full 255 off. So the budget allows a few such pixels (about
;; 0.05% of the 57344) and nothing more: a broken distance function or a swapped uniform
;; moves thousands.
(local default-budget {:max-pixels 32 :max-diff 255})
(local budgets {})

;; Scenes with functions of time have a golden at t = 0 and at these times too, each
;; named NAME@T (the picture of `love . --render scenes/NAME.fnl --time T`): one where
;; the shape moved (melt's drops and column), one where the light did (sundial's sun).
(local timed {:melt [3] :sundial [9]})

(fn scene-names []
  "Names of the goldens: the scenes in scenes/ and scenes/stress/ (without .fnl,
relative to scenes/, like \"seed\" or \"stress/planet\"), sorted, each followed by its
timed ones (\"melt@3\": scenes/melt.fnl at t = 3 s)."
  (let [lfs (require :lfs)
        names []]
    (each [_ folder (ipairs ["" "stress/"])]
      (when (lfs.attributes (.. "scenes/" folder) :mode)
        (each [file (lfs.dir (.. "scenes/" folder))]
          (let [name (file:match "^(.+)%.fnl$")]
            (when name (table.insert names (.. folder name)))))))
    (table.sort names)
    (let [out []]
      (each [_ name (ipairs names)]
        (table.insert out name)
        (each [_ t (ipairs (or (. timed name) []))]
          (table.insert out (.. name "@" t))))
      out)))

(fn budget-for [name]
  (or (. budgets name) default-budget))

(fn golden-path [name] (.. golden-dir "/" name ".png"))

(fn shell-quote [s] (.. "'" (s:gsub "'" "'\\''") "'"))

(fn label [name]
  ;; Golden NAME as its scene file says it: scenes/NAME.fnl, or scenes/BASE.fnl at t = T.
  (case (name:match "^(.-)@([%d.]+)$")
    (base t) (.. "scenes/" base ".fnl at t = " t " s")
    _ (.. "scenes/" name ".fnl")))

(fn render! [name out ?interpret?]
  "Render golden NAME (scenes/NAME.fnl, or NAME@T: at T seconds) with the real app into
`out` (with `?interpret?`, by the tape interpreter's shader). True, or nil and its
output."
  ;; LuaJIT's popen close does not give the exit status, so the shell prints it last.
  ;; --samples 1: the goldens are the one-ray picture (--render's default is the
  ;; player's anti-aliased still).
  (let [(scene t) (let [(base at) (name:match "^(.-)@([%d.]+)$")]
                    (if base (values base at) (values name nil)))
        cmd (string.format "SDL_VIDEODRIVER=offscreen timeout 600 love . --render %s --out %s --size %dx%d --samples 1%s%s 2>&1; echo \"exit:$?\""
                           (shell-quote (.. "scenes/" scene ".fnl")) (shell-quote out)
                           (. size 1) (. size 2) (if t (.. " --time " t) "")
                           (if ?interpret? " --interpret" ""))
        text (with-open [p (io.popen cmd)] (p:read :*a))]
    (if (text:match "exit:0%s*$")
        true
        (values nil (.. "love . --render failed for scenes/" scene ".fnl" (if t (.. " at t = " t) "") ":\n" text)))))

(fn diff [a b]
  "Compare images `a` and `b` (from png.decode): {:over n :max d :worst [x y]} where
over counts pixels whose largest channel difference exceeds the tolerance, and a diff
image (red where over, a half-bright grey copy of `a` elsewhere)."
  (assert (and (= a.width b.width) (= a.height b.height)) "images differ in size")
  (let [w a.width h a.height
        pa a.pixels pb b.pixels
        out-pixels []]
    (var over 0)
    (var worst 0)
    (var worst-at nil)
    (for [y 0 (- h 1)]
      (for [x 0 (- w 1)]
        (let [i (* 4 (+ x (* y w)))
              d (math.max (math.abs (- (. pa i) (. pb i)))
                          (math.abs (- (. pa (+ i 1)) (. pb (+ i 1))))
                          (math.abs (- (. pa (+ i 2)) (. pb (+ i 2)))))
              grey (math.floor (/ (+ (. pa i) (. pa (+ i 1)) (. pa (+ i 2))) 6))]
          (when (> d worst) (set worst d) (set worst-at [x y]))
          (if (> d channel-tolerance)
              (do (set over (+ over 1))
                  (table.insert out-pixels 255)
                  (table.insert out-pixels 0)
                  (table.insert out-pixels 0))
              (for [_ 1 3] (table.insert out-pixels grey)))
          (table.insert out-pixels 255))))
    {: over :max worst :worst worst-at
     :image {:width w :height h :pixels out-pixels}}))

(fn within-budget? [name result]
  (let [budget (budget-for name)]
    (and (<= result.over budget.max-pixels) (<= result.max budget.max-diff))))

(fn check [name ?options]
  "Render scene NAME and compare it with its golden. Returns {:status :ok|:missing|:failed
:message :new-path :diff-path :result}. Writes the new render and a diff image under
test/out/ (git-ignored); never touches test/golden/. `?options`: {:interpret? true}
draws it by the tape interpreter (the same golden and budget; its files are
NAME.interpreted.png and NAME.interpreted.diff.png)."
  (os.execute (.. "mkdir -p " out-dir "/stress"))
  (let [interpret? (?. ?options :interpret?)
        base (.. out-dir "/" name (if interpret? ".interpreted" ""))
        new-path (.. base ".png")
        diff-path (.. base ".diff.png")
        (ok? err) (render! name new-path interpret?)]
    (if (not ok?)
        {:status :failed :message err}
        (case (png.read-file (golden-path name))
          (nil gerr) (if (io.open (golden-path name) :rb)
                         {:status :failed :message gerr}
                         {:status :missing :new-path new-path
                   :message (.. (label name) " has no golden image " (golden-path name)
                                "; create it with `make golden` and look at it before committing")})
          golden (let [(new nerr) (png.read-file new-path)]
                   (if (not new)
                       {:status :failed :message nerr}
                       (let [result (diff golden new)
                             budget (budget-for name)]
                         (if (within-budget? name result)
                             {:status :ok : result :new-path new-path}
                             (do (png.write-file diff-path result.image)
                                 {:status :failed : result :new-path new-path :diff-path diff-path
                                  :message (string.format
                                            "%s differs from %s: %d pixels over %d/255 (budget %d), largest channel difference %d (budget %d) at pixel %s; new image %s, diff image %s (red: over)"
                                            (.. (label name) (if interpret? " drawn by the tape interpreter" ""))
                                            (golden-path name) result.over channel-tolerance
                                            budget.max-pixels result.max budget.max-diff
                                            (if result.worst (.. (. result.worst 1) "," (. result.worst 2)) "-")
                                            new-path diff-path)})))))))))

(fn copy-file [from to]
  (let [data (with-open [f (assert (io.open from :rb))] (f:read :*a))]
    (with-open [f (assert (io.open to :wb))] (f:write data))))

(fn update! []
  "Regenerate the goldens that are missing or fail their budget; print what changed.
Returns the number of scenes whose render failed."
  (os.execute (.. "mkdir -p " golden-dir "/stress"))
  (var failures 0)
  (each [_ name (ipairs (scene-names))]
    (let [r (check name)]
      (case r.status
        :ok (print (string.format "unchanged  %s (%d pixels over tolerance)" name r.result.over))
        :missing (do (copy-file r.new-path (golden-path name))
                     (print (.. "created    " (golden-path name))))
        :failed (if r.result
                    (do (copy-file r.new-path (golden-path name))
                        (print (.. "updated    " (golden-path name) ": " r.message)))
                    (do (set failures (+ failures 1))
                        (print (.. "FAILED     " name ": " r.message)))))))
  failures)

{: check : update! : scene-names : diff : size : budgets : default-budget : channel-tolerance}
