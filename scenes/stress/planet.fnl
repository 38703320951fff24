;; Stress: a planet, a sphere of radius 1e6, seen from 0.25 above its surface looking
;; level, so its horizon (about 707 units away) is in view, with a unit sphere standing
;; on it. The sphere's distance is length(p - centre) - 1e6: in float32 both terms are
;; near 1e6, where the spacing is 0.0625, so the distance the GPU computes near the
;; camera is only known to a few hundredths, while the double reference is exact.
;; Shadow and mirror rays start 2e-6 * (1 + distance) off the ground, far inside that
;; error: on the GPU they find the ground they leave (see the pending check in
;; test/stress_spec.fnl).
{:name "stress planet"
 :camera {:pos [0 0 0.25] :yaw 90 :pitch 0 :fov 60}
 :light {:pos [-30 20 20]}
 :objects [{:kind :sphere :radius 1000000 :pos [0 0 -1000000] :color [0.3 0.6 0.35]}
           {:kind :sphere :radius 1 :pos [0.5 12 1] :color [0.8 0.3 0.2]}]}
