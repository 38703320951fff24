;; tier: fast
;; Loops over a table's keys: Debian 12's LuaJIT (2.1 of 2022-03-20) ends a loop
;; over `pairs` (LuaJIT's ITERN bytecode, chosen by the name `pairs` or `next`) early
;; once it is despecialised (LuaJIT issue 827, fixed upstream in 2022-04). The
;; modules of src/ loop over `pairs` under another name, a plain iterator call
;; (src/util/wire.fnl says why).
(local fennel (require :fennel))
(local {: sh} (require :test.support.app))

(local modules
  (with-open [p (io.popen "find src -name '*.fnl' | sort")]
    (icollect [line (p:lines)] line)))

(fn read [path]
  (with-open [f (assert (io.open path))] (f:read :*a)))

(describe "loops over keys"
  (fn []
    (it "finds the modules" (fn [] (assert.is_true (> (length modules) 100))))
    (each [_ path (ipairs modules)]
      (it (.. path " compiles no loop to LuaJIT's ITERN (a loop over pairs or next by name)")
        (fn []
          (let [code (fennel.compileString (read path) {:filename path :allowedGlobals false})]
            (assert.is_nil (code:find "in%s+pairs%s*%(") (.. path ": a loop over pairs"))
            (assert.is_nil (code:find "in%s+next%s*[,%(]") (.. path ": a loop over next"))))))
    (it "a deep tree crosses the wire intact in 30 fresh processes (the first round trip failed in about 1 of 6)"
      (fn []
        (for [run 1 30]
          (let [(code out) (sh "luajit tools/fnl.lua test/support/wire-deep.fnl")]
            (assert.are.equal 0 code out)
            (assert.are.equal "intact" (out:match "^%s*(.-)%s*$") (.. "run " run))))))))
