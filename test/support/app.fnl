;; Commands the specs run, above all the app itself (`love .` headless): each gives
;; the command's exit code and what it printed.

;; A run that takes longer than this is stuck, not slow: the limit only catches a hang.
;; These runs take seconds alone; two cores shared with other work made 3 s runs take
;; over 30 s (issue 41), and a verdict must not depend on that.
(local hang-seconds 300)

(fn read-file [path]
  (case (io.open path :rb)
    f (with-open [f f] (f:read :*a))))

(fn sh [command ?options]
  "Run `command` in a shell: its exit code, then its standard output with its standard
error in it (2>&1 after the command), as written. With `options.stderr` true its
standard error is kept apart: the output is standard output alone, and standard error
comes third."
  (let [err-path (when (?. ?options :stderr) (os.tmpname))
        text (with-open [p (io.popen (.. command (if err-path (.. " 2>" err-path) " 2>&1")
                                         "; echo \"exit:$?\""))]
               (p:read :*a))
        err (when err-path
              (let [e (read-file err-path)] (os.remove err-path) e))]
    (values (tonumber (text:match "exit:(%d+)%s*$"))
            (pick-values 1 (text:gsub "exit:%d+%s*$" ""))
            err)))

(fn love [args ?options]
  "Run `love . ARGS` headless (SDL_VIDEODRIVER=offscreen) under `timeout`, after
`options.timeout` seconds (default hang-seconds); what `sh` gives (which takes
`options` too)."
  (sh (.. "SDL_VIDEODRIVER=offscreen timeout " (or (?. ?options :timeout) hang-seconds)
          " love . " args)
      ?options))

;; The project's folder, where the specs run (for commands run from another one).
(local root (with-open [p (io.popen "pwd")] (p:read :*l)))

(fn edit-latency-check [scene flag label]
  "Run `love . --edit-latency SCENE FLAG`, a check mode of src/app/edit-latency.fnl
that prints one line starting with `label` (': ok' when all held), and print that
line. Returns :ok, :pending (the driver keeps no shared cache: no compile helper) or
:failed, then the line (or all it printed)."
  ;; The limits only catch a hang.
  (let [(code out) (sh (.. "SDL_VIDEODRIVER=offscreen EDIT_LATENCY_LIMIT=600 timeout 1200 love . --edit-latency "
                           scene " " flag))
        line (out:match (.. label ": [^\n]*"))]
    (print (.. "\n" (or line out)))
    (values (if (not (and (= code 0) line)) :failed
                (line:find "no compile helper here" 1 true) :pending
                (line:find (.. label ": ok") 1 true) :ok
                :failed)
            (if line (.. line (if (= code 0) "" (.. " (exit " (tostring code) ")"))) out))))

{: sh : love : root : hang-seconds : edit-latency-check}
