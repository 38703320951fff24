;; Child processes that talk in frames, through LuaJIT's FFI on Linux: a child is
;; started with posix_spawnp, its standard input and output both one end of a Unix
;; socket pair (so the parent sends with MSG_NOSIGNAL: a child that died never kills
;; the parent with SIGPIPE, and receives with MSG_DONTWAIT: the parent never blocks
;; past its own deadline). A frame is "<length>\n" and that many bytes.
;;
;; Used by the scene worker (src/scene/worker.fnl): the child may hang in one C call,
;; so every wait here has a deadline, after which the caller kills the child.
;;
;; The child's standard error is a socket of its own too, never this process's: what
;; it writes there (a scene's Fennel warnings, or anything code that got out of the
;; scene's sandbox writes) is read here while waiting on the child, and passed on to
;; this process's standard error one line at a time, control characters escaped (no
;; terminal escape sequence gets through), each distinct line once and at most
;; `stderr-lines` of them a request; the rest are counted. A child that writes without
;; end only fills its socket, which every wait drains.

(local filestat (require :src.util.filestat))

(local libc (require :src.util.libc))
(local ffi libc.ffi)

(local native
  (when (and ffi (= ffi.os :Linux))
    (libc.declare [:socketpair :posix_spawn_file_actions_init
                   :posix_spawn_file_actions_destroy :posix_spawn_file_actions_adddup2
                   :posix_spawnp :send :recv :close :kill :waitpid :rm_pollfd_t :poll
                   :environ :strerror :readlink :sysconf])))

;; Linux constants (the same on x86-64 and arm64).
(local af-unix 1)
(local sock-stream 1)
(local sock-cloexec 0x80000)
(local msg-dontwait 0x40)
(local msg-nosignal 0x4000)
(local pollin 0x1)
(local pollout 0x4)
(local sigkill 9)
(local eintr 4)
(local eagain 11)

;; Lines of a child's standard error passed on a request (see the top), and the
;; longest line kept whole (a longer one is cut there).
(local stderr-lines 20)
(local stderr-line-max 2000)

;; The longest frame a parent accepts (a scene of 200,000 objects is about 30 MB).
(local max-frame (* 256 1024 1024))
(local chunk (* 1024 1024))

(fn supported? []
  "Whether child processes can be started here (Linux, LuaJIT's FFI)."
  (not= nil native))

(fn self-exe []
  "The path of the program this process runs (/proc/self/exe), or nil."
  (when native
    (let [buf (ffi.new "char[4096]")
          n (tonumber (native.readlink "/proc/self/exe" buf 4096))]
      (when (< 0 n 4096) (ffi.string buf n)))))

(fn spawn [argv]
  "Start the program `argv`[1] (looked up on PATH) with the arguments that follow, its
standard input and output a socket to this process, its standard error another (see
the top). Returns a child {:pid :fd :err-fd}, or nil and a message."
  (if (not native)
      (values nil "child processes need LuaJIT's FFI on Linux")
      (let [sv (ffi.new "int[2]")
            ev (ffi.new "int[2]")]
        (if (not= 0 (native.socketpair af-unix (+ sock-stream sock-cloexec) 0 sv))
            (values nil (.. "cannot make a socket pair: " (libc.error-text)))
            (not= 0 (native.socketpair af-unix (+ sock-stream sock-cloexec) 0 ev))
            (let [why (libc.error-text)]
              (native.close (. sv 0))
              (native.close (. sv 1))
              (values nil (.. "cannot make a socket pair: " why)))
            (let [fa (ffi.new "uint8_t[256]")   ; posix_spawn_file_actions_t is 80 bytes
                  pid (ffi.new "int[1]")
                  args (icollect [_ a (ipairs argv)] (tostring a))
                  c-argv (ffi.new "char *[?]" (+ (length args) 1))
                  keep []]
              (each [i a (ipairs args)]
                (let [s (ffi.new "char[?]" (+ (length a) 1) a)]
                  (table.insert keep s)
                  (tset c-argv (- i 1) s)))
              (native.posix_spawn_file_actions_init fa)
              (native.posix_spawn_file_actions_adddup2 fa (. sv 1) 0)
              (native.posix_spawn_file_actions_adddup2 fa (. sv 1) 1)
              (native.posix_spawn_file_actions_adddup2 fa (. ev 1) 2)
              (let [rc (native.posix_spawnp pid (. args 1) fa nil c-argv native.environ)]
                (native.posix_spawn_file_actions_destroy fa)
                (native.close (. sv 1))
                (native.close (. ev 1))
                (if (= rc 0)
                    {:pid (. pid 0) :fd (. sv 0) :parts [] :have 0 :keep keep
                     :err-fd (. ev 0) :err {:partial "" :shown 0 :hidden 0 :seen {}}}
                    (do (native.close (. sv 0))
                        (native.close (. ev 0))
                        (values nil (.. "cannot start " (. args 1) ": "
                                        (libc.error-text rc)))))))))))

(local control-chars (.. "[%c" (string.char 127) "]"))

(fn escaped [line]
  ;; `line` with every control character (and DEL) written as \xNN, a tab as four
  ;; spaces: text only.
  (pick-values 1 (line:gsub control-chars
                            #(if (= $ "\t") "    " (string.format "\\x%02x" (string.byte $))))))

(fn pass-line! [err line]
  ;; One line of a child's standard error: passed on once (see the top), or counted.
  (let [text (escaped (line:sub 1 stderr-line-max))]
    (if (or (. err.seen text) (>= err.shown stderr-lines))
        (set err.hidden (+ err.hidden 1))
        (do (tset err.seen text true)
            (set err.shown (+ err.shown 1))
            (io.stderr:write (.. "scene worker: " text "\n"))))))

(fn drain-stderr! [child]
  ;; Read what the child has written to its standard error, and pass its lines on;
  ;; at its end (the child closed it or ended) close it here too.
  (let [buf (ffi.new "char[?]" 65536)
        err child.err]
    (var open? true)
    (var more? true)
    (while (and open? more?)
      (let [n (tonumber (native.recv child.err-fd buf 65536 msg-dontwait))]
        (if (> n 0)
            (let [text (.. err.partial (ffi.string buf n))
                  last (accumulate [at 1 line-end (text:gmatch "()\n")]
                         (do (pass-line! err (text:sub at (- line-end 1))) (+ line-end 1)))
                  rest (text:sub last)]
              ;; A line past the longest kept is passed on cut (and its rest dropped).
              (set err.partial (if (> (length rest) stderr-line-max)
                                   (do (pass-line! err rest) "")
                                   rest)))
            (and (< n 0) (= (ffi.errno) eintr)) nil
            (and (< n 0) (= (ffi.errno) eagain)) (set more? false)
            (set open? false))))
    (when (not open?)
      (when (not= err.partial "") (pass-line! err err.partial))
      (set err.partial "")
      (native.close child.err-fd)
      (set child.err-fd nil))))

(fn stderr-summary! [child]
  "Say how many lines of `child`'s standard error were not passed on since the last
summary (repeats, and those past the first few), and count afresh."
  (let [err child.err]
    (when (and err (> err.hidden 0))
      (io.stderr:write (string.format "scene worker: %d more line%s of its standard error not shown (repeats, or past the first %d)\n"
                                      err.hidden (if (= err.hidden 1) "" "s") stderr-lines)))
    (when err
      (set err.hidden 0)
      (set err.shown 0)
      (set err.seen {}))))

(fn wait-for [child events deadline]
  ;; Poll the child's socket for `events` until `deadline` (monotonic seconds): true
  ;; when ready, false when the deadline passed. Its standard error is drained
  ;; meanwhile (a child blocked writing there would never answer).
  (let [p (ffi.new "rm_pollfd_t[2]")]
    (tset p 0 :fd child.fd)
    (tset p 0 :events events)
    (tset p 1 :events pollin)
    (var ready nil)
    (while (= nil ready)
      (tset p 1 :fd (or child.err-fd -1))
      (tset p 1 :revents 0)
      (let [left (- deadline (filestat.monotonic))]
        (if (< left 0) (set ready false)
            (let [n (native.poll p 2 (math.max 0 (math.min 100 (math.ceil (* left 1000)))))]
              (when (and (> n 0) child.err-fd (not= 0 (. p 1 :revents)))
                (drain-stderr! child))
              (when (and (> n 0) (not= 0 (. p 0 :revents))) (set ready true))
              (when (and (< n 0) (not= (ffi.errno) eintr)) (set ready true))))))
    ready))

(fn send! [child payload deadline]
  "Send `payload` as one frame to `child` by `deadline` (monotonic seconds). True, or
nil and :timeout or :closed."
  (stderr-summary! child)
  (let [data (.. (length payload) "\n" payload)
        total (length data)]
    (var sent 0)
    (var result nil)
    (while (= nil result)
      (if (>= sent total) (set result true)
          (not (wait-for child pollout deadline)) (set result :timeout)
          (let [n (tonumber (native.send child.fd (+ (ffi.cast "const char *" data) sent)
                                         (- total sent) (+ msg-dontwait msg-nosignal)))]
            (if (> n 0) (set sent (+ sent n))
                (and (< n 0) (or (= (ffi.errno) eagain) (= (ffi.errno) eintr))) nil
                (set result :closed)))))
    (if (= result true) true (values nil result))))

(fn frame-size [head]
  ;; The whole size of the frame that `head` starts ("<length>\n" and the payload),
  ;; false when it does not start with one, nil when the length is not all there.
  (let [nl (head:find "\n" 1 true)]
    (if (not nl) (if (> (length head) 20) false nil)
        (let [digits (head:sub 1 (- nl 1))
              n (and (digits:match "^%d+$") (tonumber digits))]
          (if (or (not n) (> n max-frame)) false
              (+ nl n))))))

(fn take-frame [child]
  ;; A whole frame's payload from what was received (child.parts, child.have bytes),
  ;; false when it is not a frame, nil when more is needed. The parts are joined once
  ;; a frame is whole (joining at every chunk would copy a 13 MB answer 200 times).
  (when (and (= nil child.need) (> child.have 0))
    (let [head (table.concat child.parts)]
      (set child.parts [head])
      (set child.need (frame-size (head:sub 1 32)))))
  (if (= child.need false) false
      (and child.need (>= child.have child.need))
      ;; The payload (after the length's line, up to `need`) and what follows it, each
      ;; joined once from the parts: joining them all first, then cutting the payload
      ;; out of that, held three copies of a 140 MB answer at once.
      (let [need child.need
            nl (: (. child.parts 1) :find "\n" 1 true)
            payload []
            rest []]
        (var pos 0)
        (each [_ part (ipairs child.parts)]
          (let [stop (+ pos (length part))
                lo (math.max (+ pos 1) (+ nl 1))
                hi (math.min stop need)]
            (when (<= lo hi) (table.insert payload (part:sub (- lo pos) (- hi pos))))
            (when (> stop need) (table.insert rest (part:sub (- (math.max (+ pos 1) (+ need 1)) pos))))
            (set pos stop)))
        (let [rest (table.concat rest)]
          (set child.parts [rest])
          (set child.have (length rest))
          (set child.need nil)
          (table.concat payload)))
      nil))

(fn receive! [child deadline]
  "The next frame from `child`, waiting until `deadline` (monotonic seconds); or nil
and :timeout (nothing whole yet: call again later, the part read is kept), :closed
(the child ended or closed its output) or :malformed (not a frame)."
  (let [buf (ffi.new "char[?]" chunk)]
    (var frame (take-frame child))
    (var why nil)
    (while (and (= nil frame) (= nil why))
      (if (not (wait-for child pollin deadline)) (set why :timeout)
          (let [n (tonumber (native.recv child.fd buf chunk msg-dontwait))]
            (if (> n 0)
                (do (table.insert child.parts (ffi.string buf n))
                    (set child.have (+ child.have n))
                    (set frame (take-frame child)))
                (and (< n 0) (or (= (ffi.errno) eagain) (= (ffi.errno) eintr))) nil
                (set why :closed)))))
    ;; With an answer, what the child wrote before it is all in its standard error's
    ;; socket: passed on now, and the lines held back counted.
    (when (and frame child.err-fd) (drain-stderr! child))
    (when frame (stderr-summary! child))
    (if (= frame false) (values nil :malformed)
        frame frame
        (values nil why))))

(local clock-ticks
  ;; Units of the CPU times in /proc/PID/stat (sysconf(_SC_CLK_TCK), 100 on Linux).
  (let [(ok? n) (pcall #(tonumber (native.sysconf 2)))]
    (if (and ok? n (> n 0)) n 100)))

(fn cpu-seconds [child]
  "Seconds of CPU `child` has used (user and system, from /proc), or nil when it
cannot be read (the child has ended)."
  (case (io.open (.. "/proc/" child.pid "/stat") :rb)
    f (let [text (f:read "*a")
            _ (f:close)
            ;; After the command name in parentheses (which may hold anything):
            ;; state is field 3, utime 14, stime 15.
            fields (icollect [w (: (or (text:match "%) (.*)$") "") :gmatch "%S+")] w)
            user (tonumber (. fields 12))
            system (tonumber (. fields 13))]
        (when (and user system) (/ (+ user system) clock-ticks)))
    _ nil))

(local wnohang 1)

(fn ended [child ?wait]
  "How `child` ended, once it has (it is then reaped): {:code N} when it exited with
status N, {:signal N} when signal N ended it; nil while it still runs after waiting
`?wait` seconds (default 0) for it to end. Asked again, the same answer."
  (when (and (not child.status) (not child.reaped?))
    (let [st (ffi.new "int[1]")
          deadline (+ (filestat.monotonic) (or ?wait 0))]
      (var done? false)
      (while (not done?)
        (let [pid (native.waitpid child.pid st wnohang)
              s (. st 0)]
          (if (= pid child.pid)
              (do (set child.reaped? true)
                  (set child.status (if (= 0 (% s 128))
                                        {:code (% (math.floor (/ s 256)) 256)}
                                        {:signal (% s 128)}))
                  (set done? true))
              (or (< pid 0) (>= (filestat.monotonic) deadline)) (set done? true)
              ;; Not yet: 10 ms (poll with no descriptors sleeps).
              (native.poll nil 0 10))))))
  child.status)

(fn kill! [child]
  "End `child` at once (SIGKILL), wait for it and close its socket."
  (when (not child.reaped?)
    (native.kill child.pid sigkill)
    (native.waitpid child.pid (ffi.new "int[1]") 0)
    (set child.reaped? true))
  ;; The child has ended: what it wrote is all there, then the end of the stream.
  (when child.err-fd (drain-stderr! child))
  (when child.err-fd
    (native.close child.err-fd)
    (set child.err-fd nil))
  (stderr-summary! child)
  (when child.fd
    (native.close child.fd)
    (set child.fd nil)))

{: supported? : self-exe : cpu-seconds : spawn : send! : receive! : kill! : ended
 : stderr-summary! : max-frame : escaped}
