;; Small scalar and vector helpers of the CPU reference (src/reference.fnl). Vectors
;; travel as multiple values (x y z).

(local sqrt math.sqrt)

(fn clamp01 [v]
  "v clamped to [0, 1]."
  (if (< v 0) 0 (> v 1) 1 v))

(fn normalize [x y z]
  "x y z scaled to unit length (the zero vector gives NaNs)."
  (let [len (sqrt (+ (* x x) (* y y) (* z z)))]
    (values (/ x len) (/ y len) (/ z len))))

(fn safe-normalize [x y z]
  "x y z scaled to unit length; the zero vector gives 0 0 1."
  (let [len (sqrt (+ (* x x) (* y y) (* z z)))]
    (if (> len 0) (values (/ x len) (/ y len) (/ z len)) (values 0 0 1))))

(fn mix [a b w]
  "GLSL's mix: a + (b - a) w, written a (1 - w) + b w."
  (+ (* a (- 1 w)) (* b w)))

(fn smoothstep [e0 e1 x]
  "GLSL's smoothstep."
  (let [t (clamp01 (/ (- x e0) (- e1 e0)))]
    (* t t (- 3 (* 2 t)))))

{: clamp01 : normalize : safe-normalize : mix : smoothstep}
