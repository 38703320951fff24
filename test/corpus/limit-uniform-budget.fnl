;; expect: test/corpus/limit-uniform-budget.fnl: objects: the scene needs 4098 uniform vectors but the driver allows 4096 (32 are reserved); remove objects worth 2 vectors (a sphere takes 2)
{:objects (fcollect [i 1 2033] {:kind :sphere :pos [i 0 0]})}
