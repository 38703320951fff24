;; expect: test/corpus/range-fov-180.fnl:2: camera.fov: must be a number of degrees from 0.1 to 179, got 180
{:camera {:fov 180}
 :objects []}
