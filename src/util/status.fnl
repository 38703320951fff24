;; Progress of long command-line work on stderr: on a terminal one line rewritten in
;; place (\r), in a log (stderr not a terminal) one line an update, so that updates
;; never run together.

(local ffi (let [(ok? m) (pcall require :ffi)] (when ok? m)))

(local terminal?
  (let [isatty (when ffi
                 (pcall ffi.cdef "int isatty(int fd);")
                 (let [(ok? f) (pcall #(. ffi.C :isatty))] (when ok? f)))]
    (and isatty (= 1 (isatty 2)))))

(fn update! [line]
  "Show `line` as the latest progress."
  (io.stderr:write (if terminal? (.. "\r" line) (.. line "\n")))
  (io.stderr:flush))

(fn done! []
  "End the progress: the next output starts on a line of its own."
  (when terminal? (io.stderr:write "\n")))

{: update! : done! : terminal?}
