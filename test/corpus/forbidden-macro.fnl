;; expect: test/corpus/forbidden-macro.fnl:2: (macro ...) is not allowed: scene files are data and run no compile-time code
(macro touch [] (os.execute "touch test/out/corpus-trace/macro"))
(touch)
{:objects []}
