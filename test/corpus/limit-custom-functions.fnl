;; expect: test/corpus/limit-custom-functions.fnl: objects[1]: the shader would hold 540 tree nodes written out, more than 500 (compiling grows faster than their number); this object writes 54 of them. A custom function counts one node for every 64 of its operations per point, once however many objects use it: write it shorter, or let objects share one function (their numbers in :params)
;; Ten distinct custom functions of about 3,400 operations per point each: each counts
;; 54 written nodes (one for every 64 operations), 540 in all. Thirty of them took
;; 16 s and 440 MB to compile on llvmpipe before they were counted.
{:objects
 [
  {:kind :custom :pos [0 0 1] :bounds [1.2 1.2 1.2]
   :distance (fn [x y z] (var d (- (math.sqrt (+ (* x x) (* y y) (* z z))) 1))
               (for [i 1 60] (set d (+ d (* 0.0001 (math.sin (+ x 0.0 (* y 0.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 0.1 (* y 1.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 0.2 (* y 2.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 0.3 (* y 3.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 0.4 (* y 4.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 0.5 (* y 5.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 0.6 (* y 6.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 0.7 (* y 7.5)))))))
               d)}
  {:kind :custom :pos [3 0 1] :bounds [1.2 1.2 1.2]
   :distance (fn [x y z] (var d (- (math.sqrt (+ (* x x) (* y y) (* z z))) 1))
               (for [i 1 60] (set d (+ d (* 0.0001 (math.sin (+ x 1.0 (* y 0.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 1.1 (* y 1.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 1.2 (* y 2.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 1.3 (* y 3.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 1.4 (* y 4.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 1.5 (* y 5.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 1.6 (* y 6.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 1.7 (* y 7.5)))))))
               d)}
  {:kind :custom :pos [6 0 1] :bounds [1.2 1.2 1.2]
   :distance (fn [x y z] (var d (- (math.sqrt (+ (* x x) (* y y) (* z z))) 1))
               (for [i 1 60] (set d (+ d (* 0.0001 (math.sin (+ x 2.0 (* y 0.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 2.1 (* y 1.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 2.2 (* y 2.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 2.3 (* y 3.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 2.4 (* y 4.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 2.5 (* y 5.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 2.6 (* y 6.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 2.7 (* y 7.5)))))))
               d)}
  {:kind :custom :pos [9 0 1] :bounds [1.2 1.2 1.2]
   :distance (fn [x y z] (var d (- (math.sqrt (+ (* x x) (* y y) (* z z))) 1))
               (for [i 1 60] (set d (+ d (* 0.0001 (math.sin (+ x 3.0 (* y 0.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 3.1 (* y 1.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 3.2 (* y 2.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 3.3 (* y 3.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 3.4 (* y 4.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 3.5 (* y 5.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 3.6 (* y 6.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 3.7 (* y 7.5)))))))
               d)}
  {:kind :custom :pos [12 0 1] :bounds [1.2 1.2 1.2]
   :distance (fn [x y z] (var d (- (math.sqrt (+ (* x x) (* y y) (* z z))) 1))
               (for [i 1 60] (set d (+ d (* 0.0001 (math.sin (+ x 4.0 (* y 0.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 4.1 (* y 1.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 4.2 (* y 2.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 4.3 (* y 3.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 4.4 (* y 4.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 4.5 (* y 5.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 4.6 (* y 6.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 4.7 (* y 7.5)))))))
               d)}
  {:kind :custom :pos [0 3 1] :bounds [1.2 1.2 1.2]
   :distance (fn [x y z] (var d (- (math.sqrt (+ (* x x) (* y y) (* z z))) 1))
               (for [i 1 60] (set d (+ d (* 0.0001 (math.sin (+ x 5.0 (* y 0.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 5.1 (* y 1.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 5.2 (* y 2.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 5.3 (* y 3.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 5.4 (* y 4.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 5.5 (* y 5.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 5.6 (* y 6.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 5.7 (* y 7.5)))))))
               d)}
  {:kind :custom :pos [3 3 1] :bounds [1.2 1.2 1.2]
   :distance (fn [x y z] (var d (- (math.sqrt (+ (* x x) (* y y) (* z z))) 1))
               (for [i 1 60] (set d (+ d (* 0.0001 (math.sin (+ x 6.0 (* y 0.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 6.1 (* y 1.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 6.2 (* y 2.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 6.3 (* y 3.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 6.4 (* y 4.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 6.5 (* y 5.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 6.6 (* y 6.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 6.7 (* y 7.5)))))))
               d)}
  {:kind :custom :pos [6 3 1] :bounds [1.2 1.2 1.2]
   :distance (fn [x y z] (var d (- (math.sqrt (+ (* x x) (* y y) (* z z))) 1))
               (for [i 1 60] (set d (+ d (* 0.0001 (math.sin (+ x 7.0 (* y 0.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 7.1 (* y 1.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 7.2 (* y 2.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 7.3 (* y 3.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 7.4 (* y 4.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 7.5 (* y 5.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 7.6 (* y 6.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 7.7 (* y 7.5)))))))
               d)}
  {:kind :custom :pos [9 3 1] :bounds [1.2 1.2 1.2]
   :distance (fn [x y z] (var d (- (math.sqrt (+ (* x x) (* y y) (* z z))) 1))
               (for [i 1 60] (set d (+ d (* 0.0001 (math.sin (+ x 8.0 (* y 0.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 8.1 (* y 1.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 8.2 (* y 2.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 8.3 (* y 3.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 8.4 (* y 4.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 8.5 (* y 5.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 8.6 (* y 6.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 8.7 (* y 7.5)))))))
               d)}
  {:kind :custom :pos [12 3 1] :bounds [1.2 1.2 1.2]
   :distance (fn [x y z] (var d (- (math.sqrt (+ (* x x) (* y y) (* z z))) 1))
               (for [i 1 60] (set d (+ d (* 0.0001 (math.sin (+ x 9.0 (* y 0.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 9.1 (* y 1.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 9.2 (* y 2.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 9.3 (* y 3.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 9.4 (* y 4.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 9.5 (* y 5.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 9.6 (* y 6.5)))))) (set d (+ d (* 0.0001 (math.sin (+ x 9.7 (* y 7.5)))))))
               d)}]}
