;; expect: test/corpus/inf-fov.fnl:2: camera.fov: must be a number of degrees above 0 and below 180, got inf
{:camera {:fov (/ 1 0)}
 :objects []}
