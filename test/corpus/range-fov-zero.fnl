;; expect: test/corpus/range-fov-zero.fnl:2: camera.fov: must be a number of degrees from 0.1 to 179, got 0
{:camera {:fov 0}
 :objects []}
