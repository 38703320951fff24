;; expect: test/corpus/limit-concat-operands.fnl: the scene needs more memory than the scene worker has (1536 MB)
;; 64 MB made by doubling (within the sandbox's memory limit), then one `..` of 30 of
;; them: a single allocation of 1920 MB, which no hook sees before it is made.
(var s (string.rep :x 1048576))
(for [i 1 6] (set s (.. s s)))
(local big (.. s s s s s s s s s s s s s s s s s s s s s s s s s s s s s s))
{:objects [{:kind :sphere :radius (length big)}]}
