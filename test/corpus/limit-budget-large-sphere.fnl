;; expect: test/corpus/limit-budget-large-sphere.fnl: objects: the scene needs 4097 uniform vectors but the driver allows 4096 (32 are reserved); remove objects worth 1 vectors (a sphere of radius 1000 or more takes 3)
{:objects (fcollect [i 1 1355] {:kind :sphere :radius 5000 :pos [0 0 (* i -1)]})}
