;; expect: test/corpus/type-camera-yaw-string.fnl:2: camera.yaw: must be a number from -1e7 to 1e7, got "north"
{:camera {:yaw "north"}
 :objects []}
