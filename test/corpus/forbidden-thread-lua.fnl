;; expect: test/corpus/forbidden-thread-lua.fnl:3: (lua ...) is not allowed: scene files are data and run no compile-time code
;; Raw Lua emitted by (lua "..."), built by -> after the first-word check.
{:objects [{:kind :sphere :radius (-> "os.execute('touch test/out/corpus-trace/thread-lua') or 1" lua)}]}
