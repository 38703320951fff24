;; expect: test/corpus/nan-camera-yaw.fnl:2: camera.yaw: must be a number from -1e7 to 1e7, got nan
{:camera {:yaw (/ 0 0)}
 :objects []}
