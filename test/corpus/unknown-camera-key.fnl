;; expect: test/corpus/unknown-camera-key.fnl:3: camera.fow: unknown field (did you mean :fov?); known fields: :fov :pitch :pos :yaw
{:camera {:pos [0 -10 2]
          :fow 60}
 :objects []}
