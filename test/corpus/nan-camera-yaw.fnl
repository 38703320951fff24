;; expect: test/corpus/nan-camera-yaw.fnl:2: camera.yaw: must be a finite number, got nan
{:camera {:yaw (/ 0 0)}
 :objects []}
