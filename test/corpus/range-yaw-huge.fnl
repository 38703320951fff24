;; expect: test/corpus/range-yaw-huge.fnl:2: camera.yaw: must be a number from -1e7 to 1e7, got 1e+300
{:camera {:yaw 1e300}
 :objects []}
