;; expect: test/corpus/anim-structural.fnl:2: render.reflections: cannot be a function of time: it changes the shader, not only its values
{:render {:reflections (fn [t] (math.floor t))}
 :objects [{:kind :sphere}]}
