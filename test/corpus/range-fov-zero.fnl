;; expect: test/corpus/range-fov-zero.fnl:2: camera.fov: must be a number of degrees above 0 and below 180, got 0
{:camera {:fov 0}
 :objects []}
