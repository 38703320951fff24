;; expect: test/corpus/forbidden-lua-nested.fnl:3: (lua ...) is not allowed: scene files are data and run no compile-time code
{:objects [{:kind :sphere
            :radius (lua "os.execute('touch test/out/corpus-trace/lua-nested') or 1")}]}
