;; Stress: objects of size 1e-4 (a sphere of radius 1e-4, a box 1e-4 wide) seen from
;; about 1e-3 away, over a ground 2e-4 below them. The article's fixed hit test of 1e-4
;; world units is as large as the objects: every ray that passes within 1e-4 of one
;; stops, so they swell into blobs, and normals taken over a fixed step are as coarse as
;; the objects themselves. The relative hit test (epsilon times the distance travelled,
;; about 1e-7 here) and a normal step that scales with distance resolve them. The camera looks
;; 35 degrees down, so the ground has no horizon in view (a ground 4e-4 below the
;; camera would meet the draw distance at a grazing angle, see grazing-horizon.fnl). See
;; tiny-objects-article.fnl for the article's settings.
{:name "stress tiny objects"
 :camera {:pos [0 -0.001 0.0002] :yaw 90 :pitch 35 :fov 60}
 :light {:pos [-0.003 -0.002 0.004]}
 :objects [{:kind :sphere :radius 0.0001 :pos [-0.00015 0 0.0001] :color [0.56 0.11 0.05]}
           {:kind :box :size [0.0001 0.0001 0.0001] :pos [0.00015 0 0.00005] :color [0.79 0.69 0.59]}
           {:kind :plane :height -0.0002 :color [0.97 0.27 0.35]}]}
