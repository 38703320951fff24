;; expect: test/corpus/anim-returns-function.fnl:2: camera.fov: a function of time must return a value, not another function
{:camera {:fov (fn [t] (fn [] 60))}
 :objects []}
