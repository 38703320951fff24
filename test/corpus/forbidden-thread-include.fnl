;; expect: test/corpus/forbidden-thread-include.fnl:3: (include ...) is not allowed: scene files are data and run no compile-time code
;; include reads another file at compile time.
{:objects (. (-> :scenes.seed include) :objects)}
