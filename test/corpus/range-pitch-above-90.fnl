;; expect: test/corpus/range-pitch-above-90.fnl:2: camera.pitch: must be a number of degrees from -90 to 90, got 95
{:camera {:pitch 95}
 :objects []}
