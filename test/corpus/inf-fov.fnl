;; expect: test/corpus/inf-fov.fnl:2: camera.fov: must be a number of degrees from 0.1 to 179, got inf
{:camera {:fov (/ 1 0)}
 :objects []}
