;; The command-line values of `--mesh`, checked before anything opens (a bad value fails
;; at once, not after the scene has loaded): the resolution and the region. Pure: no
;; requires.

(local min-resolution 8)
;; Memory grows with the area, four times a doubling: machined-part at 1024 cells
;; (2.5 million triangles) peaked at 1.72 GB and took 17 s, organic at 1024 1.63 GB.
(local max-resolution 1024)
(local default-resolution 128)
;; The most leaf blocks (4x4x4 cells the mesher samples) one mesh may have. Memory
;; follows them, at the peak from 8 KB a block (city at 512: 162,000 blocks, 1.34 GB)
;; to 21 KB (a unit box, every block full of surface: 98,306 at 512 took 2.07 GB,
;; 186,000 at 704 4.0 GB): at most about 3.9 GB at this many. At 128 cells a whole
;; grid has 36,000, so the default is never refused.
(local max-leaves 180224)

(fn parse-region [s]
  "The box {:lo :hi} of `s` = \"x0,y0,z0,x1,y1,z1\", or nil and a message."
  (let [nums (icollect [w (s:gmatch "[^,]+")] (tonumber w))
        fields (icollect [w (s:gmatch "[^,]+")] w)
        ok? (and (= 6 (length nums)) (= 6 (length fields))
                 (accumulate [ok? true _ v (ipairs nums)]
                   (and ok? (= v v) (< (math.abs v) math.huge))))]
    (if (not ok?)
        (values nil (.. "--region must be six numbers x0,y0,z0,x1,y1,z1, got " s))
        (let [lo [(. nums 1) (. nums 2) (. nums 3)]
              hi [(. nums 4) (. nums 5) (. nums 6)]
              bad (accumulate [b nil i axis (ipairs [:x :y :z])]
                    (or b (when (<= (. hi i) (. lo i)) axis)))]
          (if bad (values nil (string.format "--region: %s1 must be greater than %s0, got %s"
                                             bad bad s))
              {: lo : hi})))))

(fn parse-resolution [s]
  "The resolution in `s` (a whole number of cells, 8 to 1024: min-resolution to
max-resolution), or nil and a message."
  (let [n (tonumber s)]
    (if (and n (= n (math.floor n)) (>= n min-resolution) (<= n max-resolution)) n
        (values nil (string.format "--resolution must be a whole number from %d to %d, got %s"
                                   min-resolution max-resolution s)))))

(fn parse-adaptive [s]
  "The largest distance from the surface in `s` for --adaptive (a positive, finite
number in the scene's units), or nil and a message."
  (let [e (tonumber s)]
    (if (and e (> e 0) (< e math.huge)) e
        (values nil (.. "--adaptive must be a distance above 0 in the scene's units (the most a merged triangle may stray from the surface, e.g. 0.01), got " s)))))

{: parse-region : parse-resolution : parse-adaptive : default-resolution : min-resolution : max-resolution
 : max-leaves}
