;; The player itself, in a real window under Xvfb (tools/check-states.sh): a slider
;; drag, a value edit, a structural edit and an animated scene, each grabbed about six
;; times a second; no grabbed picture may mix two scene states. Left alone, the
;; picture gets its anti-aliased still. About a minute. And a scene worker that hangs
;; in a function of time: the player pauses with a message and quits on escape.
;; `make test` installs Xvfb, xdotool, xwd and bc.

(local run (. (require :test.support.app) :sh))

(fn found? [tool]
  (= 0 (run (.. "command -v " tool))))

(describe "the player under Xvfb"
  (fn []
    (let [missing (icollect [_ tool (ipairs [:xvfb-run :xdotool :xwd :bc])]
                    (when (not (found? tool)) tool))]
      (if (> (length missing) 0)
          (pending (.. "not installed: " (table.concat missing ", ") " (make test installs them)"))
          (it "never shows a picture that mixes two scene states"
            (fn []
              (let [(code out) (run "OUT=test/out/check-states bash tools/check-states.sh")]
                (print out)
                (let [mixed (tonumber (out:match "(%d+) frames? mix two states"))]
                  (assert.are.equal 0 mixed (.. "pictures mixing two states; worst frames in test/out/check-states\n" out))
                  (assert.is_truthy (out:find "anti-aliased still: " 1 true)
                                    (.. "no anti-aliased still after the structural edit\n" out))
                  ;; Exit 2 with every frame classified: a scenario whose state never
                  ;; changed within the script's waits (a machine too slow for them);
                  ;; that says nothing about mixing, so it is reported, not failed.
                  ;; Any other exit 2 (no window, the player exited) fails.
                  (if (and (= code 2) (out:find "NOT EXERCISED" 1 true))
                      (print "check-states: a scenario was not exercised on this machine: see above")
                      (assert.are.equal 0 code out)))))
          (it "pauses the clock with a message when the worker hangs in a function of time; escape quits, during a load too"
            (fn []
              ;; The worker is a stand-in that never answers an animate
              ;; (tools/check-stuck-worker.sh); the player kills it after a second.
              ;; Escape took 0.07 s here; 10 s would mean the player was stuck.
              (let [(code out) (run "OUT=test/out/check-stuck-worker bash tools/check-stuck-worker.sh")]
                (print out)
                (assert.are.equal 0 code out)
                ;; Killed by its CPU deadline, or, where the stand-in got under a
                ;; sixth of a core (a busy 2-core machine), by the wall-clock backstop
                ;; of six times that: either way the player says so and pauses.
                (assert.truthy (or (out:find "took more than 1 s of CPU (a library call that never returns?); the scene worker was stopped (the animation is paused; space plays)" 1 true)
                                   (out:find "got no answer within 6 s; the scene worker was stopped (the animation is paused; space plays)" 1 true))
                               out)
                (assert.truthy (out:match "quit [%d.]+ s after escape\n") out)
                (assert.truthy (out:match "quit [%d.]+ s after escape during a load") out)))))))))
