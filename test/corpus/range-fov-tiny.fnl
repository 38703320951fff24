;; expect: test/corpus/range-fov-tiny.fnl:2: camera.fov: must be a number of degrees from 0.1 to 179, got 1e-300
{:camera {:fov 1e-300}
 :objects []}
