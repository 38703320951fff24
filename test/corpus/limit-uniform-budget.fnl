;; expect: test/corpus/limit-uniform-budget.fnl: objects: the scene needs 4100 uniform vectors but the driver allows 4096 (32 are reserved); remove objects worth 4 vectors (a sphere of radius 1000 or more takes 3)
;; Spheres and boxes in a field take no uniforms (src/render/field.fnl); planet-sized
;; spheres keep their own uniform arrays, 3 vectors each.
{:objects (fcollect [i 1 1356] {:kind :sphere :radius 1000 :pos [(* i 3000) 0 0]})}
