;; tier: fast
;; The rays a pixel of a finished picture (src/app/quality.fnl): --render and --record
;; draw the player's still unless --quality or --samples says otherwise.
(local quality (require :src.app.quality))
(local plan-mod (require :src.render.plan))
(local scene-mod (require :src.scene.load))

(fn pick [r] [r.samples r.adaptive? r.quality r.label])

(describe "quality of a finished picture"
  (fn []
    (it "is the player's still by default: adaptive 4 x 4 in the shaded view"
      (fn []
        (assert.are.same [4 true :still "adaptive 4 x 4"] (pick (quality.resolve {} {:render {}})))
        (assert.are.same (quality.still-options)
                         {:samples (. (quality.resolve {} {:render {}}) :samples)
                          :adaptive? (. (quality.resolve {} {:render {}}) :adaptive?)})))

    (it "is one ray in the other views unless asked, as the player shows them"
      (fn []
        (assert.are.same [1 false :draft "one ray a pixel"]
                         (pick (quality.resolve {:view "normals"} {:render {}})))
        (assert.are.same [4 false :still "4 x 4 rays a pixel"]
                         (pick (quality.resolve {:view "normals" :quality "still"} {:render {}})))))

    (it "takes --samples 1 as draft, --samples N as the still with N, and final as every pixel"
      (fn []
        (assert.are.same [1 false :draft "one ray a pixel"] (pick (quality.resolve {:samples 1} {:render {}})))
        (assert.are.same [1 false :draft "one ray a pixel"] (pick (quality.resolve {:quality "draft"} {:render {}})))
        (assert.are.same [6 true :still "adaptive 6 x 6"] (pick (quality.resolve {:samples 6} {:render {}})))
        (assert.are.same [4 false :final "4 x 4 rays a pixel"] (pick (quality.resolve {:quality "final"} {:render {}})))
        (assert.are.same [8 false :final "8 x 8 rays a pixel"]
                         (pick (quality.resolve {:quality "final" :samples 8} {:render {}})))))

    (it "keeps a scene's own samples when nothing is asked, and overrides them when asked"
      (fn []
        (let [scene {:render {:samples 3 :adaptive true}}]
          (assert.are.same [3 true :scene "adaptive 3 x 3"] (pick (quality.resolve {} scene)))
          (assert.are.same [1 false :draft "one ray a pixel"] (pick (quality.resolve {:samples 1} scene)))
          (assert.are.same [4 false :final "4 x 4 rays a pixel"] (pick (quality.resolve {:quality "final"} scene))))))

    (it "gives plan options that make the still's shader, and a final that is not adaptive"
      (fn []
        (let [scene (assert (scene-mod.load-string "{:objects [{:kind :sphere :radius 1 :pos [0 5 0]}]}"
                                                   "t.fnl"))
              still (plan-mod.scene->plan scene (quality.plan-options {} scene {:fold? true}))
              player (plan-mod.scene->plan scene (doto (quality.still-options) (tset :fold? true)))
              final (plan-mod.scene->plan scene (quality.plan-options {:quality "final"} scene))
              draft (plan-mod.scene->plan scene (quality.plan-options {:samples 1} scene))]
          (assert.are.equal player.key still.key)
          (assert.are.same [4 true] [still.samples still.adaptive?])
          (assert.are.same [4 false] [final.samples final.adaptive?])
          (assert.are.same [1 false] [draft.samples draft.adaptive?]))))

    (it "lets an explicit :adaptive? false override a scene's :adaptive true"
      (fn []
        (let [scene (assert (scene-mod.load-string
                              "{:render {:samples 3 :adaptive true} :objects [{:kind :sphere :radius 1 :pos [0 5 0]}]}"
                              "t.fnl"))]
          (assert.is_true (. (plan-mod.scene->plan scene) :adaptive?))
          (assert.is_false (. (plan-mod.scene->plan scene {:samples 4 :adaptive? false}) :adaptive?)))))))
