;; expect: test/corpus/forbidden-key-huge-strings.fnl:3: (eval-compiler ...) is not allowed: scene files are data and run no compile-time code
{:objects []
 (eval-compiler (var s "") (for [i 1 15] (set s (.. s (string.rep "x" 50000000)))) :name) "big"}
