;; The state of one file for the watcher: its kind, size and modification time with
;; sub-second precision, and the wall clock in the same units. Through LuaJIT's FFI on
;; Linux (x86-64 and arm64 layouts of struct stat); elsewhere through lua-filesystem,
;; whose times are whole seconds (marked :coarse?).

(local ffi (let [(ok? m) (pcall require :ffi)] (when ok? m)))
(local lfs (let [(ok? m) (pcall require :lfs)] (when ok? m)))

(local layouts
  {:x64 "typedef struct { unsigned long dev, ino, nlink; unsigned int mode, uid, gid;
           int pad0; unsigned long rdev; long size, blksize, blocks;
           long atime, atime_ns, mtime, mtime_ns, ctime, ctime_ns; long unused[3]; }
         rm_stat_t;"
   :arm64 "typedef struct { unsigned long dev, ino; unsigned int mode, nlink, uid, gid;
             unsigned long rdev, pad1; long size; int blksize, pad2; long blocks;
             long atime, atime_ns, mtime, mtime_ns, ctime, ctime_ns; unsigned int unused[2]; }
           rm_stat_t;"})

(local native
  (when (and ffi (= ffi.os :Linux) (. layouts ffi.arch))
    (let [(ok? err) (pcall ffi.cdef (.. (. layouts ffi.arch)
                                        " typedef struct { long sec, nsec; } rm_timespec_t;
                                          int stat(const char *path, rm_stat_t *buf);
                                          int access(const char *path, int mode);
                                          int clock_gettime(int clock, rm_timespec_t *ts);"))]
      ;; stat is a real symbol from glibc 2.33 on; older ones only have __xstat.
      (when (and ok? (pcall #(. ffi.C :stat)))
        {:buf (ffi.new "rm_stat_t") :ts (ffi.new "rm_timespec_t")}))))

(local regular 0x8000)
(local directory 0x4000)

(fn now []
  "Wall-clock seconds, in the same units as `stat`'s :mtime."
  (if native
      (do (ffi.C.clock_gettime 0 native.ts)
          (+ (tonumber native.ts.sec) (* 1e-9 (tonumber native.ts.nsec))))
      (os.time)))

(fn stat [path]
  "{:kind :file|:directory|:other :size :mtime :coarse? :readable?} for `path`, or nil
when it does not exist."
  (if native
      (when (= 0 (ffi.C.stat path native.buf))
        (let [b native.buf
              mode (tonumber b.mode)
              bits (* 4096 (% (math.floor (/ mode 4096)) 16))
              kind (if (= bits regular) :file (= bits directory) :directory :other)]
          {: kind :size (tonumber b.size) :coarse? false
           :mtime (+ (tonumber b.mtime) (* 1e-9 (tonumber b.mtime_ns)))
           :readable? (= 0 (ffi.C.access path 4))}))
      lfs
      (case (lfs.attributes path)
        a {:kind (case a.mode :file :file :directory :directory _ :other)
           :size a.size :mtime a.modification :coarse? true
           :readable? (not= nil (case (io.open path :rb) f (do (f:close) true)))})))

{: stat : now :precise? (not= nil native)}
