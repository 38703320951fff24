;; tier: fast
;; Issue 43: a custom node's factor and bounds hold for every value its parameters
;; take. A function of time declares its range in :ranges and is checked over it
;; (every frame's value within it); a slider's :min and :max are its range; the
;; measures are kept across loads (a drag measures nothing again). And for loops whose
;; counter would overflow the shader's int or its float are refused.

(local fennel (require :fennel))
(local load (require :src.scene.load))
(local custom (require :src.sdf.custom))
(local translate (require :src.sdf.translate))

(fn parse [source]
  (let [(_ form) ((fennel.parser (fennel.string-stream source) "t.fnl"))] form))

(fn counting-measure []
  ;; custom.measure, counting its calls and their evaluations (its third value).
  (let [count {:calls 0 :evaluations 0}]
    (values (fn [...]
              (set count.calls (+ count.calls 1))
              (let [(m at evaluations) (custom.measure ...)]
                (set count.evaluations (+ count.evaluations (or evaluations 0)))
                (values m at evaluations)))
            count)))

(fn tree-of [scene] (. scene.objects 1 :tree))

;; A unit sphere whose distance is multiplied by r: its slope outside is r, so the
;; factor grows with r (the shape stays the unit sphere, in its bounds at every r).
(local steep "(fn [x y z r] (* r (- (math.sqrt (+ (* x x) (* y y) (* z z))) 1)))")

(fn scene [params ?extra ?prelude]
  (.. (or ?prelude "") "{:objects [{:kind :custom :bounds [1 1 1]\n :params " params "\n"
      (or ?extra "") "\n :distance " steep "}]}"))

(describe "custom: a function of time's range"
  (fn []
    (it "is required: without :ranges the load is refused, naming the field and the fix"
      (fn []
        (let [(s msg) (load.load-string (scene "{:r (fn [t] (+ 1.25 (* 0.75 (math.sin t))))}") "t.fnl")]
          (assert.is_nil s)
          (assert.are.equal "t.fnl:2: objects[1].params.r: a function of time; declare the values it takes, like :ranges {:r [0.5 2]}, so that the distance's factor holds for all of them"
                            msg))))

    (it "is measured at its ends: the factor is the larger end's (r = 2), not the load value's (1.25)"
      (fn []
        (let [(measure count) (counting-measure)
              s (assert (load.load-string (scene "{:r (fn [t] (+ 1.25 (* 0.75 (math.sin t))))}" ":ranges {:r [0.5 2]}")
                                          "t.fnl" {: measure}))
              fixed (assert (load.load-string (scene "{:r 1.25}") "t.fnl"))]
          ;; The slope outside is r exactly; central differences read it within
          ;; rounding (1e-6), and the factor is 1.1 times it (custom.limits.margin).
          (assert.are.near (* 2 custom.limits.margin) (. (tree-of s) :lipschitz) 1e-4)
          (assert.are.near (* 1.25 custom.limits.margin) (. (tree-of fixed) :lipschitz) 1e-4)
          ;; Its ends and three values between (limits.range-points).
          (assert.are.equal custom.limits.range-points count.calls)
          ;; The load value is the function's at t = 0.
          (assert.are.equal 1.25 (. (tree-of s) :params :r)))))

    (it "fails a frame whose value leaves the range, as other functions of time fail"
      (fn []
        (let [s (assert (load.load-string (scene "{:r (fn [t] (+ 1 t))}" ":ranges {:r [0.5 2]}") "t.fnl"))]
          (assert.is_true (load.animate s 0.75))
          (assert.are.equal 1.75 (. (tree-of s) :params :r))
          (let [(ok? msg) (load.animate s 1.3)]
            (assert.is_nil ok?)
            (assert.are.equal "t.fnl:2: objects[1].params.r: the function of time gave 2.3 at t = 1.3, outside its declared range [0.5 2]"
                              msg)))))

    (it "reaches the app through the scene worker: its answer and its values checked by the main process"
      (fn []
        (let [handle (. (require :src.scene.worker-main) :handle)
              answer (require :src.scene.answer)
              wire (require :src.util.wire)
              source (scene "{:r (fn [t] (+ 1 t))}" ":ranges {:r [0.5 2]}")
              a (handle {:op :load : source :file "t.fnl"})]
          (assert.is_true a.ok a.message)
          (let [s (assert (answer.check-scene (wire.decode (assert (wire.encode a))) "t.fnl" source))]
            (assert.are.near (* 2 custom.limits.margin) (. (tree-of s) :lipschitz) 1e-4)
            (assert.are.same [0.5 2] (. (tree-of s) :ranges :r))
            (assert.are.same [1.75] (answer.check-values s [1.75]))
            ;; A value the worker gives outside the range (a worker that lies: the
            ;; worker's own check says the time, below).
            (let [(ok? msg) (answer.check-values s [2.3])]
              (assert.is_nil ok?)
              (assert.truthy (msg:find "objects[1].params.r: the function of time gave 2.3, outside its declared range [0.5 2]" 1 true) msg)))
          (let [r (handle {:op :animate :t 1.3})]
            (assert.is_false r.ok)
            (assert.are.equal "t.fnl:2: objects[1].params.r: the function of time gave 2.3 at t = 1.3, outside its declared range [0.5 2]"
                              r.message)))))

    (it "refuses a load value outside the range, and ranges that are not ranges of parameters"
      (fn []
        (each [_ [params extra expected]
               (ipairs [["{:r (fn [t] 3)}" ":ranges {:r [0.5 2]}"
                         "objects[1].params.r: the function of time gave 3 at t = 0, outside its declared range [0.5 2]"]
                        ["{:r 3}" ":ranges {:r [0.5 2]}" "objects[1].params.r: is 3, outside its declared range [0.5 2]"]
                        ["{:r 1}" ":ranges {:q [0.5 2]}" "objects[1].ranges.q: is not a parameter in the node's :params"]
                        ["{:r 1}" ":ranges {:r [2 0.5]}" "objects[1].ranges.r: must be two numbers [lo hi] from -1e7 to 1e7, lo at most hi, like [0.5 2], got a list of 2 items"]
                        ["{:r 1}" ":ranges {:r 1}" "objects[1].ranges.r: must be two numbers [lo hi]"]
                        ["{:r 1}" ":ranges [1 2]" "objects[1].ranges: must be a table of the values parameters take, like {:r [0.5 2]}"]])]
          (let [(s msg) (load.load-string (scene params extra) "t.fnl")]
            (assert.is_nil s params)
            (assert.truthy (msg:find expected 1 true) (.. extra "\n=> " msg))))))

    (it "checks the bounds over the range, naming the value that crosses them"
      (fn []
        ;; A ball of radius r in bounds [1 1 1]: r = 1.5 crosses them.
        (let [(s msg) (load.load-string
                       "{:objects [{:kind :custom :bounds [1 1 1] :params {:r (fn [t] 1)} :ranges {:r [0.5 1.5]}
 :distance (fn [x y z r] (- (math.sqrt (+ (* x x) (* y y) (* z z))) r))}]}" "t.fnl")]
          (assert.is_nil s)
          (assert.truthy (msg:find "objects[1].bounds: with r = 1.5, the distance is -0.5 at " 1 true) msg)
          ;; The box suggested holds the ball at its largest (1.5, rounded up).
          (let [box (icollect [w (: (msg:match "a box that holds it: %[([^%]]*)%]") :gmatch "%S+")] (tonumber w))]
            (assert.is_true (<= 1.5 (. box 1) 1.65) msg)))))

    (it "keeps the measures of several ranged parameters within the budget"
      (fn []
        ;; A costly function (a loop of 64 turns, about 1000 operations a call) with
        ;; two ranged parameters: corners, the middle and seeded values, 12 in all,
        ;; all of them within limits.range-share times one measure's operations.
        (let [(measure count) (counting-measure)
              s (assert (load.load-string
                         "{:objects [{:kind :custom :bounds [1 1 1] :params {:r (fn [t] 1) :k (fn [t] 0.5)}
 :ranges {:r [0.8 1] :k [0 1]}
 :distance (fn [x y z r k]
             (var d 0)
             (for [i 1 64] (set d (+ d (* 0.015625 (math.sqrt (+ (* x x) (* y y) (* z z) (* k 0.001 i)))))))
             (- d r))}]}" "t.fnl" {: measure}))
              cost (. (tree-of s) :custom :cost)
              budget (* custom.limits.range-share (+ custom.limits.measure-ops custom.limits.refine-ops custom.limits.jump-ops))]
          (print (string.format "\nranged measure: %d calls, %d evaluations of %d operations (%.3g of a budget of %.3g)"
                                count.calls count.evaluations cost (* count.evaluations cost) budget))
          (assert.are.equal custom.limits.range-samples count.calls)
          (assert.is_true (> cost 500) (tostring cost))
          ;; Each call's operations: `cost` each (measure's own accounting). Within
          ;; 5%: a refinement stops at the first check past its budget, a walk's or a
          ;; climb's turn later (12 to 36 calls each).
          (assert.is_true (<= (* count.evaluations cost) (* 1.05 budget))
                          (string.format "%d evaluations of %d operations, budget %g" count.evaluations cost budget)))))))

(describe "custom: a slider's range"
  (fn []
    (it "is measured over its :min and :max: the factor from its max end, the same at every value"
      (fn []
        (each [_ [params prelude] (ipairs [["{:r (param :r 1 {:min 0.5 :max 2})}" ""]
                                           ["{:r r}" "(local r (param :r 1 {:min 0.5 :max 2}))\n"]])]
          (let [source (scene params nil prelude)]
            (each [_ value (ipairs [1 0.7])]
              (let [s (assert (load.load-string source "t.fnl" {:overrides {:r {:value value :base 1}}}))]
                (assert.are.equal value (. (tree-of s) :params :r))
                (assert.are.near (* 2 custom.limits.margin) (. (tree-of s) :lipschitz) 1e-4)))))))

    (it "is not taken for a value only computed from a slider: measured at each value a drag gives it"
      (fn []
        (let [source (scene "{:r (* 2 (param :r 0.5 {:min 0.25 :max 2}))}")]
          ;; r = 1: the unit sphere's exact distance.
          (assert.are.equal 1 (. (tree-of (assert (load.load-string source "t.fnl"))) :lipschitz))
          ;; A drag to 1.5 loads again (as the player's does), measuring r = 3 there.
          (let [s (assert (load.load-string source "t.fnl" {:overrides {:r {:value 1.5 :base 0.5}}}))]
            (assert.are.equal 3 (. (tree-of s) :params :r))
            (assert.are.near (* 3 custom.limits.margin) (. (tree-of s) :lipschitz) 1e-4)))))

    (it "is measured once: a drag's load (another value) calls no measure, a value edit does"
      (fn []
        (let [(measure count) (counting-measure)
              source (scene "{:r (param :r 1 {:min 0.5 :max 2.5})}")]
          (assert (load.load-string source "t.fnl" {: measure}))
          (assert.are.equal custom.limits.range-points count.calls)
          (assert (load.load-string source "t.fnl" {: measure :overrides {:r {:value 1.7 :base 1}}}))
          (assert (load.load-string source "t.fnl" {: measure :overrides {:r {:value 0.6 :base 1}}}))
          (assert.are.equal custom.limits.range-points count.calls)
          ;; Another range is another measure.
          (assert (load.load-string (source:gsub ":max 2%.5" ":max 3") "t.fnl" {: measure}))
          (assert.are.equal (* 2 custom.limits.range-points) count.calls))))))

(describe "custom: for loops whose counter overflows the shader's"
  (fn []
    (fn loop-fn [bounds]
      (.. "(fn [x y z] (var a 0) (for [i " bounds "] (set a (+ a 0.001))) (- x a))"))

    (it "are refused with the fix: 1e9, 2^31, 1e308, a step of 0.1 over 1e8 turns, negative steps past -2^24"
      (fn []
        (each [_ [bounds expected]
               (ipairs [["1 1e9" "a for loop may turn at most 64 times, this one turns 1000000000 times"]
                        ["1000000000 1000000003" "a for loop's counter must stay within -16777216 to 16777216 (2^24: the shader counts in a 32-bit int, read as a float exact only so far), this one reaches 1000000004; count from a small number and add the rest in the body"]
                        ["2147483645 2147483647" "this one reaches 2147483648;"]
                        ["0 2147483647 2147483647" "this one reaches 4294967294;"]
                        ["1e308 1e308" "this one reaches 1e+308;"]
                        ["0 1e7 0.1" "a for loop's bounds must be whole constant numbers"]
                        ["-16777214 -16777216 -1" "this one reaches -16777217;"]
                        ["-2147483640 -2147483648 -1" "this one reaches -2147483649;"]
                        ["1 (math.min x 1e9)" "this one turns 1000000000 times"]])]
          (let [(t msg) (translate.translate (parse (loop-fn bounds)))]
            (assert.is_nil t bounds)
            (assert.truthy (msg:find expected 1 true) (.. bounds "\n=> " msg))))))

    (it "takes a negative step, and a counter up to 2^24"
      (fn []
        (let [t (assert (translate.translate (parse "(fn [x y z] (var a 0) (for [i 10 1 -3] (set a (+ a i))) (- x a))")))]
          (assert.truthy (t.glsl:find ">= 1; i%d+ %+= %-3%)") t.glsl)
          ;; 10 + 7 + 4 + 1.
          (assert.are.equal -22 ((translate.compile-lua t.lua) 0 0 0 1)))
        (assert.truthy (translate.translate (parse (loop-fn "16777200 16777215"))))
        (assert.truthy (translate.translate (parse (loop-fn "-16777215 -16777200"))))))

    (it "are refused by the main process's check of the texts too"
      (fn []
        (let [t (assert (translate.translate (parse (loop-fn "1 3"))))
              name t.glsl-name
              glsl-header (t.glsl:match "for %(int i%d+ = 1; i%d+ <= 3; i%d+%+%+%)")
              lua-header (t.lua:match "for v%d+ = 1, 3 do")]
          (assert.truthy glsl-header t.glsl)
          (assert.truthy lua-header t.lua)
          (assert.is_true (custom.check-glsl t.glsl name))
          (assert.is_true (custom.check-lua t.lua))
          (each [_ [a b step] (ipairs [[2147483645 2147483647] [1000000000 1000000003] ["1e308" "1e308"]
                                       [0 10000000 "0.1"] [-2147483640 -2147483648 -1] [-16777214 -16777216 -1]])]
            (let [glsl (t.glsl:gsub "(for %(int )(i%d+)( = )1(; i%d+ )<= 3(; i%d+)%+%+%)"
                                    (fn [f i eq mid tail]
                                      (.. f i eq a mid (if (and step (< (tonumber step) 0)) ">= " "<= ") b tail
                                          (if step (.. " += " step) "++") ")")))
                  lua-text (t.lua:gsub "for (v%d+) = 1, 3 do" (fn [v] (.. "for " v " = " a ", " b (if step (.. ", " step) "") " do")))]
              (assert.falsy (custom.check-glsl glsl name) glsl)
              (assert.falsy (custom.check-lua lua-text) lua-text)))
          ;; A negative step within bounds passes both.
          (assert.is_true (custom.check-glsl (t.glsl:gsub "= 1; (i%d+) <= 3; (i%d+)%+%+" "= 3; %1 >= 1; %2 += -1") name))
          (assert.is_true (custom.check-lua (t.lua:gsub "for (v%d+) = 1, 3 do" "for %1 = 3, 1, -1 do"))))))))
