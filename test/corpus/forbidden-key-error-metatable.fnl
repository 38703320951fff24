;; expect: test/corpus/forbidden-key-error-metatable.fnl:3: (eval-compiler ...) is not allowed: scene files are data and run no compile-time code
{:objects []
 (eval-compiler (error (setmetatable {} {:__tostring (fn [] (error "boom"))}))) 1}
