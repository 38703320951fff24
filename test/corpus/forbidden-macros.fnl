;; expect: test/corpus/forbidden-macros.fnl:2: (macros ...) is not allowed: scene files are data and run no compile-time code
(macros {:touch (fn [] (os.execute "touch test/out/corpus-trace/macros"))})
(touch)
{:objects []}
