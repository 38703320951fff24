;; expect: test/corpus/forbidden-macrodebug.fnl:2: (macrodebug ...) is not allowed: scene files are data and run no compile-time code
{:objects [] :name (macrodebug (when true 1) true)}
