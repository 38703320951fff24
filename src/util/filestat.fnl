;; The state of one file for the watcher and the output writer: its kind, size,
;; modification time with sub-second precision, device, inode and permission bits, and
;; the wall clock in the same units. Through LuaJIT's FFI on
;; Linux (x86-64 and arm64: src/util/libc.fnl has both layouts of struct stat);
;; elsewhere through lua-filesystem, whose times are whole seconds (marked :coarse?).

(local libc (require :src.util.libc))
(local ffi libc.ffi)
(local lfs (let [(ok? m) (pcall require :lfs)] (when ok? m)))

(local native
  (when (and ffi (= ffi.os :Linux)
             (libc.declare [:rm_stat_t :rm_timespec_t :stat :lstat :access :clock_gettime]))
    {:buf (ffi.new "rm_stat_t") :ts (ffi.new "rm_timespec_t")}))

;; The file-type bits of st_mode, by name (the same on every POSIX system).
(local kinds {0x8000 :file 0x4000 :directory 0x1000 :fifo 0xC000 :socket
              0x2000 :char-device 0x6000 :block-device 0xA000 :link})

;; lua-filesystem's names for the same.
(local lfs-kinds {:file :file :directory :directory "named pipe" :fifo :socket :socket
                  "char device" :char-device "block device" :block-device :link :link})

(fn now []
  "Wall-clock seconds, in the same units as `stat`'s :mtime."
  (if native
      (do (ffi.C.clock_gettime 0 native.ts)
          (+ (tonumber native.ts.sec) (* 1e-9 (tonumber native.ts.nsec))))
      (os.time)))

(fn monotonic []
  "Seconds of a clock that only goes forward (CLOCK_MONOTONIC), for timing; without
the FFI, os.clock (the process's CPU time)."
  (if native
      (do (ffi.C.clock_gettime 1 native.ts)
          (+ (tonumber native.ts.sec) (* 1e-9 (tonumber native.ts.nsec))))
      (os.clock)))

(fn native-stat [f path]
  (when (= 0 (f path native.buf))
    (let [b native.buf
          mode (tonumber b.mode)
          type (or (. kinds (* 4096 (% (math.floor (/ mode 4096)) 16))) :other)]
      {:kind (if (or (= type :file) (= type :directory)) type :other)
       : type :size (tonumber b.size) :coarse? false
       :mtime (+ (tonumber b.mtime) (* 1e-9 (tonumber b.mtime_ns)))
       :dev (tonumber b.dev) :ino (tonumber b.ino) :perm (% mode 4096)
       :readable? (= 0 (ffi.C.access path 4))})))

(fn lfs-stat [f path]
  (case (f path)
    a (let [type (or (. lfs-kinds a.mode) :other)]
        {:kind (if (or (= type :file) (= type :directory)) type :other)
         : type :size a.size :mtime a.modification :coarse? true
         :dev a.dev :ino a.ino
         :perm (accumulate [n 0 i c (a.permissions:gmatch "()(.)")]
                 (if (= c "-") n (+ n (^ 2 (- 9 i)))))
         ;; Opening a FIFO to see whether it is readable would wait for a writer.
         :readable? (and (= type :file)
                         (not= nil (case (io.open path :rb) f (do (f:close) true))))})))

(fn stat [path]
  "{:kind :file|:directory|:other :type :size :mtime :coarse? :readable? :dev :ino
:perm} for `path` (links followed), or nil when it does not exist. :type is :file,
:directory, :fifo, :socket, :char-device, :block-device or :other; :perm the
permission bits."
  (if native (native-stat ffi.C.stat path)
      lfs (lfs-stat lfs.attributes path)))

(fn lstat [path]
  "As `stat`, but of a symbolic link itself (its :type is then :link)."
  (if native (native-stat ffi.C.lstat path)
      (and lfs lfs.symlinkattributes) (lfs-stat lfs.symlinkattributes path)))

{: stat : lstat : now : monotonic :precise? (not= nil native)}
