;; expect: test/corpus/forbidden-thread-eval-compiler-memory.fnl:3: (eval-compiler ...) is not allowed: scene files are data and run no compile-time code
;; 2 GB built at compile time, through -> into ->>.
{:objects (-> (do (var s "x") (for [i 1 31] (set s (.. s s))) []) (->> eval-compiler))}
