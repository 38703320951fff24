;; The player driven through LÖVE's event queue (`love . --input-check`): a tapped key,
;; a click after pointer motion, F12 at a lowered render scale, ] after -, and the
;; parameter panel (drag, checkbox, colour, save into the file, reload as a value edit),
;; F9 (a mesh of the scene as shown, beside it), a structural edit waiting for the compile helper (src/app/warm.fnl), and settled
;; values drawn by the folded shader the helper built, a value edit going back to the
;; uniform one at once.
;; With the fixes undone, the first five checks fail (see the issue 13 note).

(local app (require :test.support.app))

(describe "the player's input, headless"
  (fn []
    (it "passes every input check"
      (fn []
        (let [(code out) (app.love "--input-check" {:timeout 600})]
          (assert.truthy (out:find "input checks: 0 failed" 1 true) out)
          (assert.are.equal 0 code out)
          ;; Every check ran (a check that stopped the script early would say fewer).
          (let [(_ n) (out:gsub "input check: [^\n]*: ok\n" "")]
            (assert.are.equal 24 n out)))))))
