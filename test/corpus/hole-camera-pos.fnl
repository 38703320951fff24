;; expect: test/corpus/hole-camera-pos.fnl:2: camera.pos[1]: must be a number from -1e7 to 1e7, got nil
{:camera {:pos [nil nil 5]}
 :objects []}
