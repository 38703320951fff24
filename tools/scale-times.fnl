;; Load, plan and uniform-pack times of scene files, as the app does them (the load
;; through the scene worker, plain data in this process), and peak memory:
;;   luajit tools/fnl.lua tools/scale-times.fnl W H FILE...
;; Prints one line per file: objects, seconds of load, plan and pack (wall clock),
;; and this process's and the worker's peak resident memory so far (VmHWM).
(local worker (require :src.scene.worker))
(local plan (require :src.render.plan))
(local uniforms (require :src.render.uniforms))
(local camera (require :src.render.camera))
(local filestat (require :src.util.filestat))

(fn hwm-mb [pid]
  (case (io.open (.. "/proc/" pid "/status"))
    f (let [s (f:read :*a)] (f:close) (/ (or (tonumber (s:match "VmHWM:%s*(%d+)")) 0) 1024))
    _ 0))

(fn worker-hwm-mb []
  ;; The largest peak among this process's children (the worker).
  (let [self (: (with-open [f (io.open "/proc/self/stat")] (f:read :*l)) :match "^(%d+)")
        kids (case (io.open (.. "/proc/" self "/task/" self "/children"))
               f (let [s (f:read :*a)] (f:close) s)
               _ "")]
    (accumulate [most 0 pid (kids:gmatch "%d+")] (math.max most (hwm-mb pid)))))

(fn timed [f]
  (let [t0 (filestat.monotonic)
        (a b) (f)]
    (values (- (filestat.monotonic) t0) a b)))

(let [[w h & files] arg
      w (tonumber w)
      h (tonumber h)]
  ;; The worker started before the clock runs, as in the app after its first load.
  (assert (worker.load-source "(local x 1) {:objects []}" "warm.fnl"))
  (each [_ path (ipairs files)]
    (collectgarbage)
    (let [(t-load s err) (timed #(worker.load-file path))]
      (if (not s) (print path err)
          (let [(t-plan p perr) (timed #(plan.scene->plan s))]
            (if (not p) (print path (string.format "load %.2f s; plan: %s" t-load perr))
                (let [(t-pack) (timed #(uniforms.pack s p (camera.from-scene s) w h))]
                  (print (string.format "%s: %d objects, load %.2f s, plan %.2f s, pack %.2f s; peak %.0f MB here, %.0f MB in the worker"
                                        path (length s.objects) t-load t-plan t-pack
                                        (hwm-mb :self) (worker-hwm-mb)))))))))
  (worker.kill!))
