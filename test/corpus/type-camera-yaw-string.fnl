;; expect: test/corpus/type-camera-yaw-string.fnl:2: camera.yaw: must be a finite number, got "north"
{:camera {:yaw "north"}
 :objects []}
