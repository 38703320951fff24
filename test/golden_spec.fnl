;; Golden images: every scene renders through the real app (LÖVE on Mesa) and matches
;; its PNG in test/golden/ within the scene's budget (see src/verify/golden.fnl for budgets).
(local golden (require :src.verify.golden))

(describe "golden images"
  (fn []
    (each [_ name (ipairs (golden.scene-names))]
      (it (.. name " matches test/golden/" name ".png")
        (fn []
          (let [r (golden.check name)]
            (when r.result
              (print (string.format "golden %-10s %d pixels over %d/255, largest difference %d"
                                    name r.result.over golden.channel-tolerance r.result.max)))
            (assert (= r.status :ok) r.message)))))

    (it "has goldens at a second time for the animated scenes, which show them moved"
      (fn []
        ;; --time must reach the picture: melt's drops and sundial's sun move.
        (let [png (require :src.util.png)
              names (collect [_ n (ipairs (golden.scene-names))] n true)]
          (each [_ [base timed] (ipairs [[:melt "melt@3"] [:sundial "sundial@9"]])]
            (assert.is_true (. names timed) (.. timed " is not among the goldens"))
            (let [r (golden.diff (assert (png.read-file (.. "test/golden/" base ".png")))
                                 (assert (png.read-file (.. "test/golden/" timed ".png"))))]
              (assert.is_true (> r.over 1000) (.. timed ": " r.over " pixels differ from t = 0")))))))

    (it "counts a changed image as over budget"
      (fn []
        ;; The comparison itself must see a difference: invert one image's red channel.
        (let [png (require :src.util.png)
              a (assert (png.read-file "test/golden/seed.png"))
              b (assert (png.read-file "test/golden/seed.png"))]
          (for [i 0 (- (* a.width a.height 4) 1) 4]
            (tset b.pixels i (- 255 (. b.pixels i))))
          (let [r (golden.diff a b)]
            (assert.is_true (> r.over 1000))
            (assert.is_true (> r.max 200))))))))
