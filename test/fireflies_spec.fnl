;; Specs for src/verify/fireflies.fnl: isolated extreme pixels are found, smooth
;; gradients and edges between two flat areas are not.
(local fireflies (require :src.verify.fireflies))

(fn image [width height f]
  "A reader over a width x height grey image whose value at (x, y) is (f x y)."
  (values width height (fn [x y] (let [v (f x y)] (values v v v)))))

(fn found [w h read threshold]
  (fireflies.find w h read threshold))

(describe "fireflies"
  (fn []
    (it "finds a single bright pixel and a single dark one, largest margin first"
      (fn []
        (let [(w h read) (image 8 8 #(if (and (= $1 2) (= $2 3)) 200
                                         (and (= $1 5) (= $2 5)) 20
                                         100))
              out (found w h read 40)]
          (assert.are.equal 2 (length out))
          (assert.are.same [2 3] [(. out 1 :x) (. out 1 :y)])
          (assert.is_true (< (math.abs (- (. out 1 :by) 100)) 1e-9))
          (assert.are.same [5 5] [(. out 2 :x) (. out 2 :y)]))))

    (it "ignores margins at or under the threshold"
      (fn []
        (let [(w h read) (image 8 8 #(if (and (= $1 2) (= $2 3)) 140 100))]
          (assert.are.equal 0 (length (found w h read 40))))))

    (it "finds nothing in a steep gradient or along a hard edge"
      (fn []
        (let [(w h read) (image 16 16 #(* 15 $1))]
          (assert.are.equal 0 (length (found w h read 10))))
        (let [(w h read) (image 16 16 #(if (< $1 8) 0 255))]
          (assert.are.equal 0 (length (found w h read 10))))))

    (it "reads RGBA bytes row by row from the top"
      (fn []
        (let [pixels [0 0 0 255 10 20 30 255 0 0 0 255 40 50 60 255]
              read (fireflies.rgba-reader {:width 2 :height 2
                                           :pixels (setmetatable {} {:__index #(. pixels (+ $2 1))})})]
          (assert.are.same [10 20 30] [(read 1 0)])
          (assert.are.same [40 50 60] [(read 1 1)]))))))
