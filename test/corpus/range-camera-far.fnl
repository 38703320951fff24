;; expect: test/corpus/range-camera-far.fnl:2: camera.pos[1]: must be a number from -1e7 to 1e7, got 1e+308
{:camera {:pos [1e308 0 0]}
 :objects []}
