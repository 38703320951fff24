;; Scene files of N spheres for the loader's scaling figures (tools/scale-times.fnl):
;;   luajit tools/fnl.lua tools/gen-spheres.fnl literal N OUT.fnl   -- written out, plain data
;;   luajit tools/fnl.lua tools/gen-spheres.fnl loop N OUT.fnl      -- made by a loop
;; The loop is test/fixtures/spheres-100000.fnl's with N spheres on a square grid.

(fn literal [n]
  (let [lines (fcollect [i 1 n]
                (string.format "  {:kind :sphere :radius %.3f :pos [%.3f %.3f %.3f] :color [%.3f %.3f %.3f]}"
                               (+ 0.2 (* 0.05 (% i 7))) (- (% (* i 0.37) 100) 50)
                               (- (% (* i 1.7) 100) 50) (% (* i 3.1) 40)
                               (/ (% i 10) 10) (/ (% i 13) 13) (/ (% i 17) 17)))]
    (.. "{:camera {:pos [0 -60 20] :pitch -15}\n :objects [\n" (table.concat lines "\n") "]}\n")))

(fn loop [n]
  (let [side (math.ceil (math.sqrt n))]
    (.. "(var seed 12345)
(fn rnd []
  (set seed (% (+ (* seed 1103515245) 12345) 2147483648))
  (/ seed 2147483648))
{:name \"spheres-" n "\"
 :camera {:pos [-20 -20 30] :yaw 45 :pitch 30}
 :objects (fcollect [i 0 " (- n 1) "]
            (let [x (% i " side ")
                  y (math.floor (/ i " side "))]
              {:kind :sphere
               :pos [(+ x (rnd)) (+ y (rnd)) (* 2 (rnd))]
               :radius (+ 0.1 (* 0.3 (rnd)))
               :color [(rnd) (rnd) (rnd)]}))}
")))

(let [[mode n out] arg
      n (tonumber n)
      make (case mode :literal literal :loop loop)]
  (when (not (and make n out))
    (io.stderr:write "usage: luajit tools/fnl.lua tools/gen-spheres.fnl literal|loop N OUT.fnl\n")
    (os.exit 2))
  (with-open [f (assert (io.open out :wb))] (f:write (make n))))
