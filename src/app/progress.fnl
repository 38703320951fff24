;; Progressive refinement for the player: when the full-resolution picture of a state
;; would take longer than a frame may (on a software renderer a heavy scene takes
;; seconds), it is drawn in horizontal bands from the top, one band per frame, so input
;; is read and the window redrawn between bands and escape always works. Each band is
;; as tall as fits the frame's budget at the time a row took in the band before.
;; Pure: the caller passes the render times in and draws the rows it is given.

(local budget 0.1)       ; seconds a frame may take while the picture is refined
(local max-bands 256)

(fn new [height ?seconds ?render-budget ?even?]
  "A schedule for a picture `height` rows tall, whole in `?seconds` (predicted; nil
when unknown: 4 bands), in bands whose render fits `?render-budget` (budget). With
`?even?`, every band as tall as the first, whatever they take: a pass whose times a
row are wanted all down the picture (share-above)."
  (let [render-budget (or ?render-budget budget)
        bands (if ?seconds (math.ceil (/ ?seconds render-budget)) 4)
        rows (math.max 1 (math.ceil (/ height (math.max 1 (math.min max-bands bands)))))]
    {: height : rows :next 0 : render-budget :even? ?even?}))

(fn rows [p]
  "The rows [y0 y1) to draw this frame."
  (values p.next (math.min p.height (+ p.next p.rows))))

(fn drawn! [p y0 y1 seconds]
  "The rows [y0 y1) were drawn in `seconds`: go on below them, the next band as tall
as fits the budget at that time a row (at least 1/256 of the picture; as tall as
before in an even schedule)."
  (set p.next (math.max p.next y1))
  (when (not p.even?)
    (let [per-row (/ seconds (math.max 1 (- y1 y0)))
          fit (math.floor (/ p.render-budget (math.max per-row 1e-9)))]
      (set p.rows (math.max 1 (math.ceil (/ p.height max-bands)) (math.min p.height fit))))))

(fn complete? [p]
  "True once every row has been drawn."
  (>= p.next p.height))

(fn bands [p]
  "The number of bands the picture takes at the current band height."
  (math.ceil (/ p.height p.rows)))

(fn covered [p]
  "The share of the picture drawn, 0 to 1."
  (/ p.next (math.max 1 p.height)))

(fn share-above [passed y]
  "The share of a pass's time spent on the rows above row `y`: `passed` its bands,
each [y0 y1 seconds] (a band's time spread evenly over its rows). What a later pass
over the same rows, costing as this one did row by row, has done when it reaches
`y`: a still's rays, drawn after its centre rays in even bands (src/app/render.fnl),
know where its sky was cheap. nil when the pass took no time."
  (let [total (accumulate [s 0 _ [_ _ t] (ipairs passed)] (+ s t))]
    (when (> total 0)
      (/ (accumulate [s 0 _ [y0 y1 t] (ipairs passed)]
           (+ s (* t (/ (math.max 0 (- (math.min y y1) y0)) (math.max 1 (- y1 y0))))))
         total))))

{: new : rows : drawn! : complete? : bands : covered : share-above : budget : max-bands}
