;; How many rays a pixel of a finished picture gets: the player's anti-aliased still
;; and the command line's --quality and --samples (--render, --record). One place, so
;; that `love . --render` draws the still with the player's own shader.
;; Pure: options in, plan options and a label out.

;; The still's grid: still-samples x still-samples rays where a pixel holds an edge
;; (shaders/pipeline/adaptive.glsl).
;; `pairs` under another name: a loop over `pairs` by that name is LuaJIT's ITERN,
;; which Debian 12's LuaJIT ends early once despecialised (see src/util/wire.fnl).
(local each-pair pairs)

(local still-samples 4)

(fn still-options []
  "The plan options of the player's anti-aliased still (see plan.scene->plan)."
  {:samples still-samples :adaptive? true})

(fn label [samples adaptive?]
  (if (<= samples 1) "one ray a pixel"
      adaptive? (string.format "adaptive %d x %d" samples samples)
      (string.format "%d x %d rays a pixel" samples samples)))

(fn resolve [o scene]
  "The rays a pixel for a finished picture of `scene` asked with `o` (:quality
\"draft\"|\"still\"|\"final\", :samples n, :view; each may be absent):
{:samples n :adaptive? bool :quality q :label text}. Unasked, it is the player's:
the still in the shaded view (adaptive 4 x 4), one ray in the other views, and the
scene's own :render :samples and :adaptive when it sets samples above 1 (the player
shows those and draws no still). draft is one ray; still is adaptive N x N (N from
--samples, 4); final is N x N in every pixel. Adaptive needs the shaded view's
normals: in the other views still is N x N in every pixel too."
  (let [view (or o.view :shaded)
        shaded? (= view :shaded)
        own (or (?. scene :render :samples) 1)
        quality (or o.quality
                    (when o.samples (if (= o.samples 1) :draft :still)))]
    (if (= quality nil)
        (if (> own 1)
            (let [adaptive? (and shaded? (= true (?. scene :render :adaptive)))]
              {:samples own : adaptive? :quality :scene :label (label own adaptive?)})
            shaded?
            {:samples still-samples :adaptive? true :quality :still
             :label (label still-samples true)}
            {:samples 1 :adaptive? false :quality :draft :label (label 1 false)})
        (= quality :draft)
        {:samples 1 :adaptive? false :quality :draft :label (label 1 false)}
        (let [n (or o.samples still-samples)
              adaptive? (and (= quality :still) shaded? (> n 1))]
          {:samples n : adaptive? : quality :label (label n adaptive?)}))))

(fn plan-options [o scene ?extra]
  "plan.scene->plan's options for a finished picture (see resolve), with `?extra`
(a table of further options, copied) merged in."
  (let [r (resolve o scene)
        out (collect [k v (each-pair (or ?extra {}))] k v)]
    (set out.samples r.samples)
    (set out.adaptive? r.adaptive?)
    out))

{: still-samples : still-options : resolve : plan-options : label}
