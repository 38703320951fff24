;; expect: test/corpus/forbidden-lua.fnl:2: (lua ...) is not allowed: scene files are data and run no compile-time code
(lua "os.execute('touch test/out/corpus-trace/lua')")
{:objects []}
