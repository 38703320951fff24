;; A polar-repeated flower on a capped-torus rim: petals (ellipsoids, mirrored so each
;; is symmetric), a cut-sphere seed head with a solid-angle cap, sepals by a second
;; polar repetition, and a stem of torus and cylinder pieces.
{:name "flower"
 :camera {:pos [0 -6.5 5.5] :yaw 90 :pitch 32 :fov 50}
 :light {:pos [-8 -12 20]}
 :environment [0.7 0.85 0.7]
 ;; The modern look (see docs/scenes.md, Lighting); m in the player shows the classic model.
 :lighting {:sky-zenith [0.35 0.55 0.8] :sky-horizon [0.75 0.88 0.75]
            :ambient 0.5 :ao 0.9 :ao-radius 0.3 :exposure 1.1}
 :render {:reflections 1 :draw-distance 200}
 :objects
 [{:kind :plane :height 0 :color [0.35 0.5 0.3]}
  ;; Petals: 9 around z, each a flattened ellipsoid tilted up.
  {:kind :polar :count 9 :pos [0 0 2.5] :color [0.95 0.45 0.65] :mirror 0
   :children [{:kind :mirror :normal [0 1 0]
               :children [{:kind :ellipsoid :radii [1 0.36 0.08] :rotate [0 -18 0]
                           :pos [1.15 0 0.3]}]}]}
  ;; Sepals below, 5 around.
  {:kind :polar :count 5 :pos [0 0 2.35] :color [0.3 0.6 0.25] :mirror 0
   :children [{:kind :ellipsoid :radii [0.7 0.2 0.05] :rotate [0 20 0] :pos [0.6 0 0]}]}
  ;; Seed head: a cut sphere, cut flat at the top, with a shallow solid-angle cap.
  {:kind :union :pos [0 0 2.5] :color [0.95 0.75 0.15] :mirror 0.3
   :children [{:kind :cut-sphere :radius 0.55 :cut 0.25}
              {:kind :solid-angle :angle 60 :radius 0.35 :pos [0 0 0.1] :color [0.6 0.35 0.1]}]}
  ;; Stem and a leaf ring.
  {:kind :capped-cylinder :radius 0.08 :height 2.4 :pos [0 0 1.2] :color [0.3 0.55 0.25] :mirror 0}
  {:kind :capped-torus :radius 0.6 :thickness 0.06 :angle 150 :rotate [90 0 0] :pos [0.55 0 1.1]
   :color [0.3 0.55 0.25] :mirror 0}
  ;; A pot: a torus rim on a cylinder.
  {:kind :union :color [0.7 0.4 0.25] :mirror 0
   :children [{:kind :torus :radius 0.75 :thickness 0.1 :pos [0 0 0.6]}
              {:kind :capped-cone :height 0.6 :radius1 0.5 :radius2 0.75 :pos [0 0 0.3]}]}]}
