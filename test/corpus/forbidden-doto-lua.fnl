;; expect: test/corpus/forbidden-doto-lua.fnl:3: (lua ...) is not allowed: scene files are data and run no compile-time code
;; doto puts its value first in each form, and -> makes (lua value).
{:objects [{:kind :sphere :radius (doto "1" (-> lua))}]}
