;; SIGINT and SIGTERM in the command-line modes. LÖVE turns either into a quit event in
;; its queue, which it reads only between frames: a mode that works for a long time
;; without returning to LÖVE's loop (--render, --record, --mesh, --probe) must look for
;; it itself, or the signal waits until the work is done.

;; Seconds between looks at the queue (each pumps SDL's events).
(local look-every 0.1)
(local message "stopped (SIGINT or SIGTERM)")

;; Once seen, a quit stays asked for (polling takes the event out of the queue).
(var asked false)
(var looked-at nil)

(fn asked? []
  "Whether a quit event (SIGINT, SIGTERM, the window closed) has arrived. Looks at
LÖVE's queue at most every look-every seconds; the queue's other events are dropped,
so the player, which handles its own events, must not call this."
  (let [now (and love.timer (love.timer.getTime))]
    (when (and (not asked) love.event
               (or (= looked-at nil) (= now nil) (>= (- now looked-at) look-every)))
      (set looked-at now)
      (love.event.pump)
      (each [name (love.event.poll)]
        (when (= name :quit) (set asked true))))
    asked))

{: asked? : message}
