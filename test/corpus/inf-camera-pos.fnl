;; expect: test/corpus/inf-camera-pos.fnl:2: camera.pos[3]: must be a number from -1e7 to 1e7, got inf
{:camera {:pos [0 0 (/ 1 0)]}
 :objects []}
