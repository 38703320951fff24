;; The one file writer for what the program makes for the user: a rendered PNG, recorded
;; frames, an exported shader, a saved scene. Every output is written to a new file
;; created exclusively (never an existing path, never through a link) beside its
;; target, then renamed over the target; a target reached through symbolic links is
;; the file they lead to (the links stay). A target that is a directory, a FIFO or
;; another special file, or one of the files given as :protect (the scene), is refused
;; before anything is written. Pure: plain LuaJIT (FFI on Linux; lua-filesystem and
;; plain io elsewhere, with the same checks but a narrower guard against races).
;; Failures are `nil, message` naming the path; nothing here raises.

(local filestat (require :src.util.filestat))

(local libc (require :src.util.libc))
(local ffi libc.ffi)

(local native
  (when (and ffi (= ffi.os :Linux) filestat.precise?)
    (libc.declare [:open :write :close :fsync :fchmod :rename :unlink :mkdir :realpath
                   :free :getpid :strerror])))

;; open(2) flags on Linux (the same on x86-64 and arm64): O_WRONLY | O_CREAT |
;; O_EXCL | O_CLOEXEC. O_CREAT | O_EXCL fails on any existing name, a link included.
(local exclusive-flags (+ 0x1 0x40 0x80 0x80000))
(local eexist 17)
(local eintr 4)

(local lfs (let [(ok? m) (pcall require :lfs)] (when ok? m)))

(local type-names {:directory "a directory" :fifo "a FIFO" :socket "a socket"
                   :char-device "a character device" :block-device "a block device"
                   :other "a special file"})

(fn split [path]
  "The folder and the name of `path`: \"a/b.png\" -> \"a\" \"b.png\"; \"b.png\" -> \".\"."
  (let [(dir name) (path:match "^(.*)/([^/]*)$")]
    (if (not dir) (values "." path)
        (= dir "") (values "/" name)
        (values dir name))))

(fn realpath [path]
  "`path` with every link, `.` and `..` resolved, or nil when it does not lead to an
existing file. Without FFI, `path` itself."
  (if native
      (let [p (native.realpath path nil)]
        (when (not= p nil)
          (let [s (ffi.string p)] (native.free p) s)))
      path))

(fn same-file? [a b]
  (and a b (= a.dev b.dev) (= a.ino b.ino) (not= a.ino nil)))

(fn protected [info ?protect label]
  ;; The first of the files in ?protect that `info` is, as a message.
  (accumulate [msg nil _ p (ipairs (or ?protect [])) &until msg]
    (when (same-file? info (filestat.stat p))
      (.. label ": is the scene file " p " (after following links); choose another name"))))

(fn check [path ?options]
  "Whether `path` may be written as an output. `?options`: :protect, a list of files
it must not be (the scene; compared by device and inode after following links);
:label, how messages name it (default the path). Returns {:target :dir :name :perm}
(the file to replace, links resolved; the permission bits of the file it replaces,
or nil), or nil and '<label>: reason'."
  (let [options (or ?options {})
        label (or options.label path)
        link (filestat.lstat path)
        target (if (and link (= link.type :link)) (realpath path) path)
        info (and target (filestat.stat target))]
    (if (= path "") (values nil (.. label ": an empty path; name a file"))
        (not target)
        (values nil (.. label ": is a symbolic link to nothing (or a loop of links); "
                        "refusing to write through it"))
        (and info (not= info.type :file))
        (values nil (.. label ": is " (or (. type-names info.type) "a special file")
                        "; refusing to write to it"))
        (case (and info (protected info options.protect label))
          msg (values nil msg)
          _ (let [(dir name) (split target)
                  dir-info (filestat.stat dir)]
              (if (and (not dir-info) (filestat.stat "."))
                  (values nil (.. label ": the folder " dir " does not exist"))
                  (and dir-info (not= dir-info.type :directory))
                  (values nil (.. label ": " dir " is not a folder"))
                  {: target : dir : name :perm (and info info.perm)}))))))

(var serial 0)

(fn temp-name [dir name]
  (set serial (+ serial 1))
  (string.format "%s/.%s.%d-%d-%06x.tmp" dir name (if native (native.getpid) 0) serial
                 (math.random 0 0xFFFFFF)))

(fn write-fd [fd bytes]
  ;; Every byte, retrying short writes and interrupted calls: true, or nil and why.
  (let [buf (ffi.cast "const char *" bytes)]
    (var at 0)
    (var err nil)
    (while (and (not err) (< at (length bytes)))
      (let [n (tonumber (native.write fd (+ buf at) (- (length bytes) at)))]
        (if (>= n 0) (set at (+ at n))
            (not= (ffi.errno) eintr) (set err (libc.error-text)))))
    (if err (values nil err) true)))

(fn write-native [tmp bytes perm]
  ;; Create `tmp` exclusively and fill it: true, :exists when the name is taken, or nil
  ;; and why.
  (let [fd (native.open tmp exclusive-flags (or perm 0x1A4))]
    (if (< fd 0)
        (if (= (ffi.errno) eexist) :exists (values nil (libc.error-text)))
        (let [(ok? err) (write-fd fd bytes)
              ;; The replaced file's permission bits, not the umask's.
              _ (when (and ok? perm) (native.fchmod fd perm))
              synced? (and ok? (= 0 (native.fsync fd)))
              serr (when (and ok? (not synced?)) (libc.error-text))]
          (native.close fd)
          (if (not ok?) (do (native.unlink tmp) (values nil err))
              (not synced?) (do (native.unlink tmp) (values nil serr))
              true)))))

(fn write-portable [tmp bytes]
  ;; Without FFI: a name nothing has (checked with lua-filesystem where it is there,
  ;; links included), then io.
  (if (if lfs (lfs.symlinkattributes tmp) (case (io.open tmp :rb) f (do (f:close) true)))
      :exists
      (case (io.open tmp :wb)
        f (let [(ok? err) (f:write bytes)]
            (f:close)
            (if ok? true (do (os.remove tmp) (values nil err))))
        (nil err) (values nil err))))

(fn write! [path bytes ?options]
  "Write the string `bytes` as the output file `path`: checked first (see `check`,
which takes the same `?options`), then written to a new file created exclusively
beside the target and renamed over it. Returns true, or nil and '<label>: reason'
(nothing is left behind then)."
  (let [label (or (and ?options ?options.label) path)]
    (case (check path ?options)
      (nil err) (values nil err)
      {: target : dir : name :perm ?perm}
      (do (var result nil)
          (var err nil)
          (for [_ 1 20 &until (or result err)]
            (let [tmp (temp-name dir name)]
              (case (if native (write-native tmp bytes ?perm) (write-portable tmp bytes))
                :exists nil
                true (if (if native (= 0 (native.rename tmp target)) (os.rename tmp target))
                         (set result true)
                         (let [e (if native (libc.error-text) "rename failed")]
                           (os.remove tmp)
                           (set err e)))
                (nil e) (set err e))))
          (if result true
              (values nil (.. label ": cannot write: "
                              (tostring (or err "no free temporary name in its folder")))))))))

(fn ensure-dir! [dir ?options]
  "Make sure folder `dir` exists (its parents made as needed). A path that exists and
is not a folder (following links) is refused. `?options`: :label. Returns true, or
nil and '<label>: reason'."
  (let [label (or (and ?options ?options.label) dir)
        info (filestat.stat dir)]
    (if (and info (= info.type :directory)) true
        info (values nil (.. label ": is " (if (= info.type :file) "a file"
                                               (or (. type-names info.type) "a special file"))
                             ", not a folder; refusing to write into it"))
        (and (filestat.lstat dir) (= (. (filestat.lstat dir) :type) :link))
        (values nil (.. label ": is a symbolic link to nothing; refusing to write through it"))
        (do (var err nil)
            (var at (if (= (dir:sub 1 1) "/") "" "."))
            (each [part (dir:gmatch "[^/]+") &until err]
              (set at (if (= at ".") part (.. at "/" part)))
              (when (not (filestat.stat at))
                (when (if native (not= 0 (native.mkdir at 0x1ED))
                          lfs (not (lfs.mkdir at))
                          (not (os.execute (.. "mkdir '" (at:gsub "'" "'\\''") "'"))))
                  (set err (if native (libc.error-text) "cannot make the folder")))))
            (let [final (filestat.stat dir)]
              (if (and final (= final.type :directory)) true
                  (values nil (.. label ": cannot make the folder: " (or err "not a folder")))))))))

{: check : write! : ensure-dir! : realpath}
