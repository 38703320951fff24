;; expect: test/corpus/limit-compile-case-try.fnl: compiling went past its limits (200 million steps or 128 MB) and was stopped (macros that copy their arguments, nested too deep?)
;; Nested case-try: each level copies its catch clauses into every step, so these 4 KB
;; compile for 25 s into 1.3 GB without the compiler's limits.
{:objects [] :x (case-try 1 a 2 b 3 c 4
  (catch 0 (case-try 1 a 2 b 3 c 4
    (catch 0 (case-try 1 a 2 b 3 c 4
      (catch 0 (case-try 1 a 2 b 3 c 4
        (catch 0 (case-try 1 a 2 b 3 c 4
          (catch 0 (case-try 1 a 2 b 3 c 4
            (catch 0 1
                   9 1))
                 9 (case-try 1 a 2 b 3 c 4
            (catch 0 1
                   9 1))))
               9 (case-try 1 a 2 b 3 c 4
          (catch 0 (case-try 1 a 2 b 3 c 4
            (catch 0 1
                   9 1))
                 9 (case-try 1 a 2 b 3 c 4
            (catch 0 1
                   9 1))))))
             9 (case-try 1 a 2 b 3 c 4
        (catch 0 (case-try 1 a 2 b 3 c 4
          (catch 0 (case-try 1 a 2 b 3 c 4
            (catch 0 1
                   9 1))
                 9 (case-try 1 a 2 b 3 c 4
            (catch 0 1
                   9 1))))
               9 (case-try 1 a 2 b 3 c 4
          (catch 0 (case-try 1 a 2 b 3 c 4
            (catch 0 1
                   9 1))
                 9 (case-try 1 a 2 b 3 c 4
            (catch 0 1
                   9 1))))))))
           9 (case-try 1 a 2 b 3 c 4
      (catch 0 (case-try 1 a 2 b 3 c 4
        (catch 0 (case-try 1 a 2 b 3 c 4
          (catch 0 (case-try 1 a 2 b 3 c 4
            (catch 0 1
                   9 1))
                 9 (case-try 1 a 2 b 3 c 4
            (catch 0 1
                   9 1))))
               9 (case-try 1 a 2 b 3 c 4
          (catch 0 (case-try 1 a 2 b 3 c 4
            (catch 0 1
                   9 1))
                 9 (case-try 1 a 2 b 3 c 4
            (catch 0 1
                   9 1))))))
             9 (case-try 1 a 2 b 3 c 4
        (catch 0 (case-try 1 a 2 b 3 c 4
          (catch 0 (case-try 1 a 2 b 3 c 4
            (catch 0 1
                   9 1))
                 9 (case-try 1 a 2 b 3 c 4
            (catch 0 1
                   9 1))))
               9 (case-try 1 a 2 b 3 c 4
          (catch 0 (case-try 1 a 2 b 3 c 4
            (catch 0 1
                   9 1))
                 9 (case-try 1 a 2 b 3 c 4
            (catch 0 1
                   9 1))))))))))
         9 (case-try 1 a 2 b 3 c 4
    (catch 0 (case-try 1 a 2 b 3 c 4
      (catch 0 (case-try 1 a 2 b 3 c 4
        (catch 0 (case-try 1 a 2 b 3 c 4
          (catch 0 (case-try 1 a 2 b 3 c 4
            (catch 0 1
                   9 1))
                 9 (case-try 1 a 2 b 3 c 4
            (catch 0 1
                   9 1))))
               9 (case-try 1 a 2 b 3 c 4
          (catch 0 (case-try 1 a 2 b 3 c 4
            (catch 0 1
                   9 1))
                 9 (case-try 1 a 2 b 3 c 4
            (catch 0 1
                   9 1))))))
             9 (case-try 1 a 2 b 3 c 4
        (catch 0 (case-try 1 a 2 b 3 c 4
          (catch 0 (case-try 1 a 2 b 3 c 4
            (catch 0 1
                   9 1))
                 9 (case-try 1 a 2 b 3 c 4
            (catch 0 1
                   9 1))))
               9 (case-try 1 a 2 b 3 c 4
          (catch 0 (case-try 1 a 2 b 3 c 4
            (catch 0 1
                   9 1))
                 9 (case-try 1 a 2 b 3 c 4
            (catch 0 1
                   9 1))))))))
           9 (case-try 1 a 2 b 3 c 4
      (catch 0 (case-try 1 a 2 b 3 c 4
        (catch 0 (case-try 1 a 2 b 3 c 4
          (catch 0 (case-try 1 a 2 b 3 c 4
            (catch 0 1
                   9 1))
                 9 (case-try 1 a 2 b 3 c 4
            (catch 0 1
                   9 1))))
               9 (case-try 1 a 2 b 3 c 4
          (catch 0 (case-try 1 a 2 b 3 c 4
            (catch 0 1
                   9 1))
                 9 (case-try 1 a 2 b 3 c 4
            (catch 0 1
                   9 1))))))
             9 (case-try 1 a 2 b 3 c 4
        (catch 0 (case-try 1 a 2 b 3 c 4
          (catch 0 (case-try 1 a 2 b 3 c 4
            (catch 0 1
                   9 1))
                 9 (case-try 1 a 2 b 3 c 4
            (catch 0 1
                   9 1))))
               9 (case-try 1 a 2 b 3 c 4
          (catch 0 (case-try 1 a 2 b 3 c 4
            (catch 0 1
                   9 1))
                 9 (case-try 1 a 2 b 3 c 4
            (catch 0 1
                   9 1))))))))))))}
