;; tier: fast
;; Functions of time in scene files: evaluated at t = 0 when the scene loads, and at
;; any t by load.animate, each call in the sandbox with its own small step budget,
;; every value checked as at load; only values that reach uniforms may move.

(local load (require :src.scene.load))
(local plan-mod (require :src.render.plan))

(fn load-text [text]
  (load.load-string text "anim.fnl"))

(describe "functions of time"
  (fn []
    (it "take their value at t = 0 on load, and any t through animate"
      (fn []
        (let [s (assert (load-text "{:light {:pos (fn [t] [t 0 10])}
 :objects [{:kind :sphere :radius (fn [t] (+ 1 t))}
           {:kind :union :children [{:kind :torus :thickness (fn [t] (* 0.1 (+ 1 t)))}]}]}"))]
          (assert.is_true (load.animated? s))
          (assert.are.same [0 0 10] s.light.pos)
          (assert.are.equal 1 (. s.objects 1 :radius))
          (assert.are.equal 0.1 (. s.objects 2 :tree :children 1 :thickness))
          (assert.is_true (load.animate s 2))
          (assert.are.same [2 0 10] s.light.pos)
          (assert.are.equal 3 (. s.objects 1 :radius))
          (assert.is_true (< (math.abs (- 0.3 (. s.objects 2 :tree :children 1 :thickness))) 1e-12)))))

    (it "change values, never the shader's structure"
      (fn []
        (let [s (assert (load-text "{:objects [{:kind :smooth-union :radius (fn [t] (+ 0.1 t))
            :children [{:kind :sphere} {:kind :box :pos (fn [t] [t 0 0])}]}]}"))
              p0 (assert (plan-mod.scene->plan s))]
          (load.animate s 1.5)
          (let [p1 (assert (plan-mod.scene->plan s))]
            (assert.are.equal p0.key p1.key)
            (assert.are_not.same p0.tape.rows p1.tape.rows)))))

    (it "report a value that leaves its range at some t with file, line and field"
      (fn []
        (let [s (assert (load-text "{:objects [
  {:kind :sphere :radius (fn [t] (- 1 t))}]}"))
              (ok? err) (load.animate s 2)]
          (assert.is_nil ok?)
          (assert.are.equal "anim.fnl:2: objects[1].radius: must be a positive number from 1e-6 to 1e7, got -1"
                            err))))

    (it "stop a function that runs too long, every call"
      (fn []
        (let [s (assert (load-text "{:objects [{:kind :sphere :radius (fn [t] (if (> t 1) (do (while true nil) 1) 1))}]}"))
              (ok? err) (load.animate s 2)]
          (assert.is_nil ok?)
          (assert.truthy (err:find "the function of time failed at t = 2: anim.fnl: the scene ran for more than 100000 steps" 1 true) err))))

    (it "share one budget a frame: past it the frame's values fail, naming where it ran out"
      (fn []
        ;; 50 radii whose functions take about 90,000 steps each past t = 0.3 (each
        ;; under its own 100,000): 4.5 million together, past the 1 million a frame.
        (let [heavy "{:kind :sphere :radius (fn [t] (if (> t 0.3) (do (var n 0) (for [k 1 45000] (set n (+ n k))) 1) 1))}"
              s (assert (load-text (.. "{:objects [\n" (table.concat (fcollect [_ 1 50] heavy) "\n") "]}")))
              (ok? err) (load.animate s 1)]
          (assert.is_nil ok?)
          (assert.truthy (err:match "^anim%.fnl:%d+: objects%[%d+%]%.radius: the functions of time took more than 1 million steps together for one frame %(at t = 1%): fewer of them, or cheaper ones$")
                         err)
          ;; Each frame has its own budget: a cheap one after it works.
          (assert.is_true (load.animate s 0.1)))))

    (it "refuse a file whose functions of time take more than a frame's budget at t = 0"
      (fn []
        (let [heavy "{:kind :sphere :radius (fn [t] (var n 0) (for [k 1 45000] (set n (+ n k))) 1)}"
              (s err) (load-text (.. "{:objects [\n" (table.concat (fcollect [_ 1 50] heavy) "\n") "]}"))]
          (assert.is_nil s)
          (assert.truthy (err:find "the functions of time took more than 1 million steps together for one frame (at t = 0)" 1 true)
                         err))))

    (it "are refused where they would change the shader"
      (fn []
        (let [(s err) (load-text "{:objects [{:kind :polar :count (fn [t] 6) :children [{:kind :sphere}]}]}")]
          (assert.is_nil s)
          (assert.are.equal "anim.fnl:1: objects[1].count: cannot be a function of time: it changes the shader, not only its values"
                            err))))))
