;; XDG_RUNTIME_DIR for the window system's libraries. With it unset (a headless run:
;; no display, a CI job, a container), SDL's video start tries Wayland, whose library
;; prints "error: XDG_RUNTIME_DIR is invalid or not set in the environment." before
;; SDL goes on to another driver: it reads as this program's own error, though nothing
;; failed. So before SDL starts, a private empty folder (mode 0700, made by mkdtemp)
;; stands in; Wayland finds no display in it and says nothing. Once the window exists
;; the folder is removed and the variable unset again, so that nothing is left behind
;; and child processes see the environment they were given.
;; Through LuaJIT's FFI (POSIX); elsewhere it does nothing.

(local libc (require :src.util.libc))
(local ffi libc.ffi)

(local native
  (when (and ffi (not= ffi.os :Windows))
    (libc.declare [:mkdtemp :setenv :unsetenv :rmdir])))

(local variable "XDG_RUNTIME_DIR")

(fn needed? [getenv]
  "True when libwayland would complain: XDG_RUNTIME_DIR unset or not an absolute
path, and WAYLAND_DISPLAY not an absolute socket path (which needs no folder).
`getenv` looks a variable up (os.getenv)."
  (let [dir (getenv variable)
        display (getenv "WAYLAND_DISPLAY")]
    (and (not (and dir (= "/" (dir:sub 1 1))))
         (not (and display (= "/" (display:sub 1 1)))))))

(fn ensure! []
  "When needed (see needed?), make a private empty folder and point XDG_RUNTIME_DIR
at it. Returns its path (for release!), or nil when nothing was done."
  (when (and native (needed? os.getenv))
    (let [base (let [t (os.getenv "TMPDIR")]
                 (if (and t (= "/" (t:sub 1 1))) t "/tmp"))
          template (.. base "/fennel-raymarcher-runtime-XXXXXX")
          buf (ffi.new "char[?]" (+ 1 (length template)) template)]
      (when (not= nil (native.mkdtemp buf))
        (let [path (ffi.string buf)]
          (if (= 0 (native.setenv variable path 1))
              path
              (do (native.rmdir path) nil)))))))

(fn release! [path]
  "Undo ensure!: remove its folder `path` (when it is still empty) and unset the
variable it set. Nothing for a nil `path`."
  (when (and native path (= (os.getenv variable) path))
    (native.unsetenv variable)
    (native.rmdir path))
  nil)

{: ensure! : release! : needed?}
