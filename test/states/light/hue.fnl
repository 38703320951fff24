;; test/states/hue.fnl made light (after test/states/hue-colours.fnl, as there): a
;; sphere on the floor, no shadows. A frame takes about 20-25 ms at 1280x720 on
;; llvmpipe, under the player's 25 ms for drawing the image whole in one frame
;; (src/app/progress.fnl), so even a player that refines in bands shows every picture
;; whole: `SCENES=test/states/light tools/check-states.sh` shows that the check passes
;; then.
{:name "states: hue"
 :camera camera :light light :environment sky
 :render {:reflections 0 :draw-distance 200 :shadows false}
 :objects
 [{:kind :sphere :radius 1.5 :pos [0 -3.5 1.5] :color c}
  {:kind :plane :height 0 :color c}]}
