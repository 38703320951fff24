;; tier: fast
;; Parameters (src/scene/params.fnl) and the panel's pure part (src/app/panel.fnl):
;; (param :name value {:min :max}) at load, overrides from the panel, and the write-back
;; that changes only those literals, on files with comments and odd layout.

(local load (require :src.scene.load))
(local params (require :src.scene.params))
(local panel (require :src.app.panel))

(fn write-file [path text]
  (with-open [f (assert (io.open path :wb))] (f:write text)))

(fn read-file [path]
  (with-open [f (assert (io.open path :rb))] (f:read :*a)))

;; Odd layout on purpose: comments between the tokens of a call, a name written as a
;; string, a vector over three lines with a comment inside, tabs, a value in a let.
(local odd
  ";; parameters in odd places
(let [r (param ; the size
         :radius   1.5
         {:min 0.5 :max 3})]
  {:name \"odd\"
   :render {:shadows (param \"shadows\" true)}
   :objects [{:kind :sphere :radius r :pos [0 0 r]
              :color (param :tint [0.9 ; red
                                   0.30
\t\t\t\t\t\t\t\t0.2])}   ; tabs
             {:kind :box :size (param :size [1 1 1] {:min 0.1 :max 4}) :pos [3 0 1]}
             {:kind :plane :height 0}]})
")

(fn values-of [scene]
  (collect [_ p (ipairs scene.params)] p.name p.value))

(describe "parameters"
  (fn []
    (it "give their value, and list name, kind, range and default in file order"
      (fn []
        (let [scene (assert (load.load-string odd "odd.fnl"))]
          (assert.are.equal 1.5 (. scene.objects 1 :radius))
          (assert.are.same [0.9 0.3 0.2] (. scene.objects 1 :color))
          (assert.are.same [:radius :shadows :tint :size]
                           (icollect [_ p (ipairs scene.params)] p.name))
          (assert.are.same {:name :radius :kind :number :min 0.5 :max 3 :default 1.5 :value 1.5}
                           (. scene.params 1))
          (assert.are.same [:number :switch :colour :vector]
                           (icollect [_ p (ipairs scene.params)] p.kind)))))

    (it "give the panel's value instead, while the file still says what it said"
      (fn []
        (let [overrides {:radius {:value 2 :base 1.5} :tint {:value [0 1 0] :base [0.9 0.3 0.2]}
                         ;; The file says 1 1 1 now, not 2 2 2: the file wins.
                         :size {:value [3 3 3] :base [2 2 2]}
                         ;; Out of range: pulled into it.
                         :shadows {:value 7 :base true}}
              scene (assert (load.load-string odd "odd.fnl" {: overrides}))]
          (assert.are.same {:radius 2 :tint [0 1 0] :size [1 1 1] :shadows true} (values-of scene))
          (assert.are.equal 2 (. scene.objects 1 :radius))
          (let [clamped (assert (load.load-string odd "odd.fnl"
                                                  {:overrides {:radius {:value 9 :base 1.5}}}))]
            (assert.are.equal 3 (. clamped.objects 1 :radius))))))

    (it "refuse mistakes with file:line and the parameter's name"
      (fn []
        (each [_ [source message]
               (ipairs [["{:objects [{:kind :sphere\n :radius (param :r 5 {:min 0 :max 3})}]}"
                         "b.fnl:2: (param :r ...): the value 5 is outside :min 0 :max 3"]
                        ["{:objects [{:kind :sphere :radius (param :r 1)}]}"
                         "b.fnl:1: (param :r ...): a number parameter needs {:min A :max B}"]
                        ["{:objects [{:kind :sphere :radius (param :r 1 {:min 2 :max 1})}]}"
                         "b.fnl:1: (param :r ...): :min must be below :max"]
                        ["{:objects [{:kind :sphere :radius (param 1 1)}]}"
                         "b.fnl:1: (param ...): the first argument is the parameter's name, like :radius"]
                        ["{:objects [{:kind :sphere :radius (param :r 1 {:min 0 :max 3})}\n{:kind :sphere :radius (param :r 1 {:min 0 :max 3})}]}"
                         "b.fnl:2: (param :r ...): the name is already used on line 1; each parameter is written once"]
                        ["{:objects (fcollect [i 1 3] {:kind :sphere :radius (param (.. :r i) 1 {:min 0 :max 3})})}"
                         "b.fnl:1: (param ...): the name must be written as a keyword like :radius"]
                        ["{:objects [{:kind :sphere :color (param :c [2 0 0])}]}"
                         "b.fnl:1: (param :c ...): a colour has three numbers from 0 to 1 (give :min and :max for a vector)"]
                        ["{:objects [{:kind :sphere :radius (param :r \"big\")}]}"
                         "b.fnl:1: (param :r ...): the value must be a number, true or false, or three numbers like [1 0.5 0.2]"]
                        ["{:objects [{:kind :sphere :radius (param :r 1 {:min 0 :max 3 :step 1})}]}"
                         "b.fnl:1: (param :r ...): unknown option; the options are :min and :max"]
                        ["{:objects [{:kind :sphere :radius (param :r true)}]}"
                         "b.fnl:1: objects[1].radius: must be a positive number from 1e-6 to 1e7, got true"]])]
          (assert.are.same [nil message] [(load.load-string source "b.fnl")]))))

    (it "may be used many times (one parameter), in loops and in functions of time"
      (fn []
        (let [scene (assert (load.load-string
                              "(local ring (fcollect [k 1 8] {:kind :sphere :pos [k 0 1] :radius (param :r 0.4 {:min 0.1 :max 1})}))
{:objects ring :light {:pos (fn [t] [(* t (param :speed 2 {:min 0 :max 5})) 0 10])}}"
                              "loop.fnl" {:overrides {:speed {:value 3 :base 2}}}))]
          (assert.are.same [:r :speed] (icollect [_ p (ipairs scene.params)] p.name))
          (assert.is_true (load.animate scene 2))
          (assert.are.same [6 0 10] scene.light.pos))))

    (it "are at most 64 per scene"
      (fn []
        (let [calls (table.concat (fcollect [i 1 65] (string.format "(param :p%d 1 {:min 0 :max 2})" i)) " ")]
          (assert.are.same [nil (.. "b.fnl:1: (param :p65 ...): a scene has at most 64 parameters")]
                           [(load.load-string (.. "{:objects [] :name (tostring [" calls "])}") "b.fnl")]))))))

(describe "writing parameters back"
  (fn []
    (it "changes only the literals, keeping comments, layout and unchanged spellings"
      (fn []
        (let [scene (assert (load.load-string odd "odd.fnl"
                                              {:overrides {:radius {:value 2.25 :base 1.5}
                                                           :tint {:value [0.9 0.5 0.2] :base [0.9 0.3 0.2]}
                                                           :shadows {:value false :base true}}}))
              (text n) (params.write-back odd "odd.fnl" scene.params)]
          (assert.are.equal 3 n)
          (assert.are.equal (-> odd
                                (string.gsub ":radius   1%.5" ":radius   2.25")
                                (string.gsub "\"shadows\" true" "\"shadows\" false")
                                (string.gsub "0%.30\n" "0.5\n"))
                            text)
          ;; What was written loads back to the same values.
          (assert.are.same (values-of scene) (values-of (assert (load.load-string text "odd.fnl")))))))

    (it "writes numbers that read back as the slider's value"
      (fn []
        (each [_ v (ipairs [0.875 1.0015 0.5 2.99999 1e-5])]
          (let [src "{:objects [] :name (tostring (param :x 1 {:min 0 :max 3}))}"
                (text) (params.write-back src "f.fnl" [{:name :x :kind :number :value v}])
                scene (assert (load.load-string text "f.fnl"))]
            (assert.is_true (< (math.abs (- (. scene.params 1 :value) v)) (* 1e-6 v)) text)))))

    (it "says why it cannot: a value that is not a literal, a parameter gone from the file"
      (fn []
        (assert.are.same [nil "f.fnl:1: (param :x ...): its value is not written as a literal, so it cannot be saved"]
                         [(params.write-back "{:objects [] :n (param :x (+ 1 1) {:min 0 :max 3})}" "f.fnl"
                                             [{:name :x :kind :number :value 1}])])
        (assert.are.same [nil "f.fnl: the parameter :y is no longer in the file"]
                         [(params.write-back "{:objects [] :n (param :x 1 {:min 0 :max 3})}" "f.fnl"
                                             [{:name :y :kind :number :value 1}])])))

    (it "saves atomically, re-reading the file so edits made since the load are kept"
      (fn []
        (let [path (.. (os.tmpname) "-params.fnl")
              scene (assert (load.load-string odd path {:overrides {:radius {:value 2 :base 1.5}}}))
              edited (string.gsub odd ";; parameters in odd places" ";; edited in an editor meanwhile")]
          (write-file path edited)
          (assert.are.equal 1 (params.save! path scene.params))
          (assert.are.equal (string.gsub edited ":radius   1%.5" ":radius   2") (read-file path))
          (assert.is_nil (io.open (.. path ".saving") :rb))
          ;; Nothing to change: the file is not touched.
          (let [scene2 (assert (load.load-file path))]
            (assert.are.equal 0 (params.save! path scene2.params)))
          (os.remove path)
          (let [(ok? msg) (params.save! path scene.params)]
            (assert.is_nil ok?)
            (assert.truthy (msg:find "cannot read the scene file to save" 1 true))))))))

(describe "the parameter panel's layout"
  (fn []
    (let [scene (assert (load.load-string odd "odd.fnl"))
          lay (panel.layout scene.params 1280)
          labels (icollect [_ item (ipairs lay.items)] item.label)]
      (it "has a row per number and switch, three per colour and vector, and two buttons"
        (fn []
          (assert.are.same ["radius" "shadows" "tint r" "tint g" "tint b" "size x" "size y" "size z"
                            "Save to file (ctrl+s)" "Reset to file"]
                           labels)
          (assert.is_true (<= (+ lay.x lay.w) 1280))))
      (it "finds the item under the pointer, the panel's background, or nothing"
        (fn []
          (let [slider (. lay.items 1)]
            (assert.are.equal slider (panel.hit lay (+ slider.x 1) (+ slider.y 1)))
            (assert.are.equal :panel (panel.hit lay (+ lay.x 1) (+ lay.y 1)))
            (assert.is_nil (panel.hit lay 10 10)))))
      (it "maps a slider's first and last pixel to its range, in 1/1000 steps"
        (fn []
          (let [slider (. lay.items 1)
                last-x (+ slider.x slider.w -1)]
            (assert.are.equal 0.5 (panel.slider-value slider slider.x))
            (assert.are.equal 3 (panel.slider-value slider last-x))
            (assert.are.equal 3 (panel.slider-value slider (+ last-x 100)))
            (assert.are.equal 0.5 (panel.slider-value slider -5))
            (let [v (panel.slider-value slider (+ slider.x 37))]
              (assert.is_true (< (math.abs (- (/ (- v 0.5) 0.0025) (math.floor (+ 0.5 (/ (- v 0.5) 0.0025))))) 1e-6))))))
      (it "sets one component of a colour"
        (fn []
          (assert.are.same [0.9 0.7 0.2] (panel.with-value (. lay.items 4) 0.7)))))))
