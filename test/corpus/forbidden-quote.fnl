;; expect: test/corpus/forbidden-quote.fnl:3: (quote ...) is not allowed: scene files are data and run no compile-time code
{:objects []
 :name (quote x)}
