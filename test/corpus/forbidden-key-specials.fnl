;; expect: test/corpus/forbidden-key-specials.fnl:2: (eval-compiler ...) is not allowed: scene files are data and run no compile-time code
{(do (eval-compiler (tset _SPECIALS :local (fn [...] (os.execute "touch test/out/corpus-trace/specials")))) :environment) [1 1 1]
 :objects []}
