;; expect: test/corpus/type-camera-number.fnl:2: camera: must be a table like {:fov ...}, got 5
{:camera 5
 :objects []}
