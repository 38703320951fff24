;; Lines of the player's HUD that are plain text from plain values. Pure.

(fn pitch-text [pitch]
  "The camera's pitch as the keys name it: e pitches up, q down. A scene file's
:pitch (the article's) is positive looking down; the HUD says which way instead of a
sign that would read the other way: -12 is \"12.0 up\", 12 \"12.0 down\"."
  (let [shown (string.format "%.1f" (math.abs pitch))]
    (if (= shown "0.0") "0.0"
        (< pitch 0) (.. shown " up")
        (.. shown " down"))))

(fn camera-line [cam]
  "The HUD's line for camera `cam` ({:pos [x y z] :yaw :pitch}): its position, yaw
and pitch (see pitch-text)."
  (string.format "pos: %.2f %.2f %.2f  yaw %.1f  pitch %s" (. cam.pos 1) (. cam.pos 2)
                 (. cam.pos 3) cam.yaw (pitch-text cam.pitch)))

{: pitch-text : camera-line}
