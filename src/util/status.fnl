;; Progress of long command-line work on stderr: on a terminal one line rewritten in
;; place (a carriage return, the line, then "erase to the end of the line", so that a
;; shorter update leaves nothing of a longer one behind), ended by a newline; in a log
;; (stderr not a terminal) one plain line an update, so that updates never run
;; together and no control character reaches the file.

(local libc (require :src.util.libc))

(local isatty (case (libc.declare [:isatty]) c c.isatty))

(local terminal? (not (not (and isatty (= 1 (isatty 2))))))

;; "\r", the line, and CSI K: erase from the cursor to the end of the line.
(local erase-to-end "\027[K")

(fn new [stream terminal?]
  "A progress writer on `stream` (a file: write and flush), for a terminal when
`terminal?`: {:update! (fn [line]) :done! (fn [])}."
  (var open? false)
  {:update! (fn [line]
              (stream:write (if terminal? (.. "\r" line erase-to-end) (.. line "\n")))
              (set open? true)
              (stream:flush))
   :done! (fn []
            ;; On a terminal the last update stays, and the next output starts below it.
            (when (and terminal? open?) (stream:write "\n") (stream:flush))
            (set open? false))})

(local stderr (new io.stderr terminal?))

(fn update! [line]
  "Show `line` as the latest progress on stderr."
  (stderr.update! line))

(fn done! []
  "End the progress: the next output starts on a line of its own."
  (stderr.done!))

{: update! : done! : terminal? : new}
