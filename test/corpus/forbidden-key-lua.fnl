;; expect: test/corpus/forbidden-key-lua.fnl:3: (lua ...) is not allowed: scene files are data and run no compile-time code
{:objects []
 (lua "os.execute('touch test/out/corpus-trace/key-lua')") 1}
