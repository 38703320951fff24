;; expect: test/corpus/forbidden-thread-macro.fnl:3: (macros ...) is not allowed: scene files are data and run no compile-time code
;; A macro defined through ->, whose body would loop forever when (boom) expands.
(-> {:boom (fn [] (while true nil))} macros)
{:objects [(boom)]}
