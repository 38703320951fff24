;; A test scene for tools/check-states.sh (SCENES=test/states/field), after
;; test/states/hue-colours.fnl (the :hue machinery) as test/states/hue.fnl is, over a
;; field of marched members (issue 29): 60 rotated tori and 40 capsules, each placed
;; and coloured alone, so the field holds them and their colour lives in its objects
;; texture (a value edit uploads the texels it changed; a function of time changes
;; them every frame).
(var seed 5)
(fn rnd [] (set seed (% (+ (* seed 1103515245) 12345) 2147483648)) (/ seed 2147483648))

(local tori (fcollect [_ 1 60]
              {:kind :torus :radius 0.5 :thickness 0.15 :color c
               :pos [(- (* 16 (rnd)) 8) (- (* 16 (rnd)) 8) 0.6] :rotate [(* 90 (rnd)) 0 (* 90 (rnd))]}))
(local capsules (fcollect [_ 1 40]
                  {:kind :capsule :a [-0.4 0 0] :b [0.4 0 0.2] :radius 0.2 :color c
                   :pos [(- (* 16 (rnd)) 8) (- (* 16 (rnd)) 8) (+ 0.4 (* 2 (rnd)))]
                   :rotate [0 0 (* 180 (rnd))]}))

(local members tori)
(each [_ o (ipairs capsules)] (table.insert members o))

{:name "states: hue over a field of marched members"
 :camera camera :light light :environment sky
 :render {:reflections 0 :draw-distance 200}
 :objects
 [{:kind :plane :height 0 :color c :mirror 0}
  (table.unpack members)]}
