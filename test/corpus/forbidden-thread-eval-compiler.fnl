;; expect: test/corpus/forbidden-thread-eval-compiler.fnl:4: (eval-compiler ...) is not allowed: scene files are data and run no compile-time code
;; The threading macro builds (eval-compiler ...) after the first-word check has run.
{:objects [{:kind :sphere
            :radius (-> (do (length (. (require :scenes.seed) :objects))) eval-compiler)}]}
