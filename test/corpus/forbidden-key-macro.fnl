;; expect: test/corpus/forbidden-key-macro.fnl:2: (macro ...) is not allowed: scene files are data and run no compile-time code
{(macro m [] (os.execute "touch test/out/corpus-trace/key-macro")) 1
 :objects []}
