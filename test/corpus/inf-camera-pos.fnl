;; expect: test/corpus/inf-camera-pos.fnl:2: camera.pos[3]: must be a finite number, got inf
{:camera {:pos [0 0 (/ 1 0)]}
 :objects []}
