;; expect: test/corpus/range-fov-180.fnl:2: camera.fov: must be a number of degrees above 0 and below 180, got 180
{:camera {:fov 180}
 :objects []}
