;; The parameter panel: a slider for each number, three for a colour (with a swatch)
;; or a vector, a checkbox for each switch, and Save / Reset buttons, over the right
;; side of the window. Layout, hit testing and slider values are pure (tested under
;; LuaJIT); only `draw!` calls LÖVE.

(local width 300)        ; pixels
(local row-height 22)
(local label-width 112)
(local margin 8)
(local slider-steps 1000) ; a slider's value moves in 1/1000 of its range

(fn component-names [kind]
  (if (= kind :colour) ["r" "g" "b"] ["x" "y" "z"]))

(fn layout [params window-width]
  "Rectangles of the panel for `params` (the scene's :params) in a window
`window-width` wide: {:x :y :w :h :items [...]}, where each item is {:kind :slider
:checkbox :save or :reset, :param, :component (1..3 for colours and vectors), :x :y
:w :h, :label}."
  (let [x (math.max 0 (- window-width width margin))
        items []
        slider-x (+ x margin label-width)
        slider-w (- width (* 2 margin) label-width)]
    (var y (+ margin 24))
    (each [_ p (ipairs params)]
      (case p.kind
        :number (table.insert items {:kind :slider :param p :x slider-x :y y :w slider-w
                                     :h row-height :label p.name})
        :switch (table.insert items {:kind :checkbox :param p :x slider-x :y y :w row-height
                                     :h row-height :label p.name})
        _ (each [i c (ipairs (component-names p.kind))]
            (table.insert items {:kind :slider :param p :component i :x slider-x :y y
                                 :w slider-w :h row-height
                                 :label (.. p.name " " c)})
            (when (< i 3) (set y (+ y row-height)))))
      (set y (+ y row-height 4)))
    (let [button-w (/ (- width (* 3 margin)) 2)]
      (table.insert items {:kind :save :x (+ x margin) :y (+ y 4) :w button-w :h row-height
                           :label "Save to file (ctrl+s)"})
      (table.insert items {:kind :reset :x (+ x (* 2 margin) button-w) :y (+ y 4) :w button-w
                           :h row-height :label "Reset to file"}))
    {: x :y margin :w width :h (+ (- y margin) row-height 16) : items}))

(fn inside? [r mx my]
  (and (>= mx r.x) (< mx (+ r.x r.w)) (>= my r.y) (< my (+ r.y r.h))))

(fn hit [lay mx my]
  "The item of layout `lay` under the pointer at (mx, my), :panel for the panel's
background, or nil outside the panel."
  (or (accumulate [found nil _ item (ipairs lay.items) &until found]
        (when (inside? item mx my) item))
      (when (inside? lay mx my) :panel)))

(fn range-of [p]
  (if (= p.kind :colour) (values 0 1) (values p.min p.max)))

(fn slider-value [item mx]
  "The value a slider `item` takes with the pointer at x = `mx`: its range mapped
over the slider's pixels (the first gives the minimum, the last the maximum),
clamped, in steps of 1/1000 of the range."
  (let [(lo hi) (range-of item.param)
        t (math.max 0 (math.min 1 (/ (- mx item.x) (math.max 1 (- item.w 1)))))
        step (/ (- hi lo) slider-steps)
        v (+ lo (* step (math.floor (+ 0.5 (/ (* t (- hi lo)) step)))))]
    (math.max lo (math.min hi v))))

(fn item-value [item]
  (let [v item.param.value]
    (if item.component (. v item.component) v)))

(fn with-value [item v]
  "The parameter's whole value once `item` (a slider or one component of one) is set
to `v`: a number, or a new list of three."
  (let [old item.param.value]
    (if item.component
        (doto [(. old 1) (. old 2) (. old 3)] (tset item.component v))
        v)))

(fn fraction [item]
  (let [(lo hi) (range-of item.param)]
    (/ (- (item-value item) lo) (- hi lo))))

(fn value-text [v]
  (if (= (type v) :boolean) (tostring v) (string.format "%.4g" v)))

(fn draw! [lay status]
  "Draw the panel of layout `lay` with LÖVE; `status` is the line under its title
(saved, unsaved changes, an error)."
  (let [g love.graphics
        font (g.getFont)
        text-y (fn [item] (+ item.y (/ (- item.h (font:getHeight)) 2)))]
    (g.setColor 0 0 0 0.7)
    (g.rectangle :fill lay.x lay.y lay.w lay.h)
    (g.setColor 1 1 1 1)
    (g.print (.. "Parameters (F2 hides)  " status) (+ lay.x margin) (+ lay.y 4))
    (each [_ item (ipairs lay.items)]
      (case item.kind
        :slider
        (let [p item.param
              f (fraction item)
              tint (if (= p.kind :colour) (case item.component 1 [0.9 0.3 0.3] 2 [0.3 0.8 0.3] 3 [0.35 0.45 1])
                       [0.45 0.65 0.95])]
          (g.setColor 1 1 1 1)
          (g.print (.. item.label " " (value-text (item-value item))) (+ lay.x margin) (text-y item))
          (g.setColor 0.25 0.25 0.25 1)
          (g.rectangle :fill item.x (+ item.y 6) item.w (- item.h 12))
          (g.setColor (. tint 1) (. tint 2) (. tint 3) 1)
          (g.rectangle :fill item.x (+ item.y 6) (* f item.w) (- item.h 12))
          (g.setColor 1 1 1 1)
          (g.rectangle :fill (- (+ item.x (* f item.w)) 2) (+ item.y 3) 4 (- item.h 6))
          (when (and (= p.kind :colour) (= item.component 1))
            (let [[r gg b] p.value]
              (g.setColor r gg b 1)
              (g.rectangle :fill (- item.x 22) (+ item.y item.h) 16 16))))
        :checkbox
        (do (g.setColor 1 1 1 1)
            (g.print item.label (+ lay.x margin) (text-y item))
            (g.rectangle :line (+ item.x 3) (+ item.y 3) (- item.w 6) (- item.h 6))
            (when item.param.value
              (g.rectangle :fill (+ item.x 6) (+ item.y 6) (- item.w 12) (- item.h 12))))
        _ (do (g.setColor 0.3 0.3 0.35 1)
              (g.rectangle :fill item.x item.y item.w item.h)
              (g.setColor 1 1 1 1)
              (g.printf item.label item.x (text-y item) item.w :center))))
    (g.setColor 1 1 1 1)))

{: layout : hit : slider-value : with-value : draw!}
