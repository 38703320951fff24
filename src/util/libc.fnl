;; The C functions and types the program calls through LuaJIT's FFI, each declared
;; once, here: the C library's (child processes, limits, files, the clock, the
;; terminal, the environment) and zlib's (for src/util/png.fnl). A module asks for
;; the names it uses with `declare` and gets ffi.C when all of them are there, or nil,
;; and then takes its fallback (lua-filesystem, plain io, nothing). Without LuaJIT's
;; FFI (plain Lua) nothing here is declared and `ffi` is nil.
;;
;; ffi.cdef raises on a second declaration of a name, even an identical one; here a
;; name is declared at most once per process, and a declaration that fails (another
;; library declared the name first) is not an error: what counts is whether the name
;; then resolves.

(local ffi (let [(ok? m) (pcall require :ffi)] (when ok? m)))

;; struct stat, by architecture (Linux).
(local stat-layouts
  {:x64 "typedef struct { unsigned long dev, ino, nlink; unsigned int mode, uid, gid;
           int pad0; unsigned long rdev; long size, blksize, blocks;
           long atime, atime_ns, mtime, mtime_ns, ctime, ctime_ns; long unused[3]; }
         rm_stat_t;"
   :arm64 "typedef struct { unsigned long dev, ino; unsigned int mode, nlink, uid, gid;
             unsigned long rdev, pad1; long size; int blksize, pad2; long blocks;
             long atime, atime_ns, mtime, mtime_ns, ctime, ctime_ns; unsigned int unused[2]; }
           rm_stat_t;"})

;; Name -> [declaration name-it-needs ...]. A type's name starts with rm_ (no clash
;; with a system header's); its declaration is nil where its layout is not known.
(local declarations
  {;; Types.
   :rm_pollfd_t ["typedef struct { int fd; short events; short revents; } rm_pollfd_t;"]
   :rm_rlimit_t ["typedef struct { unsigned long cur, max; } rm_rlimit_t;"]
   :rm_timeval_t ["typedef struct { long sec, usec; } rm_timeval_t;"]
   :rm_rusage_t ["typedef struct { rm_timeval_t utime, stime; long rest[14]; } rm_rusage_t;"
                 :rm_timeval_t]
   :rm_sock_filter_t ["typedef struct { unsigned short code; unsigned char jt, jf; unsigned int k; } rm_sock_filter_t;"]
   :rm_sock_fprog_t ["typedef struct { unsigned short len; rm_sock_filter_t *filter; } rm_sock_fprog_t;"
                     :rm_sock_filter_t]
   :rm_timespec_t ["typedef struct { long sec, nsec; } rm_timespec_t;"]
   :rm_stat_t [(when ffi (. stat-layouts ffi.arch))]
   ;; Errors.
   :strerror ["char *strerror(int errnum);"]
   ;; Processes.
   :socketpair ["int socketpair(int domain, int type, int protocol, int sv[2]);"]
   :posix_spawn_file_actions_init ["int posix_spawn_file_actions_init(void *fa);"]
   :posix_spawn_file_actions_destroy ["int posix_spawn_file_actions_destroy(void *fa);"]
   :posix_spawn_file_actions_adddup2
   ["int posix_spawn_file_actions_adddup2(void *fa, int fd, int newfd);"]
   :posix_spawnp ["int posix_spawnp(int *pid, const char *file, const void *fa, const void *attr,
                                    char *const argv[], char *const envp[]);"]
   :send ["long send(int fd, const void *buf, unsigned long n, int flags);"]
   :recv ["long recv(int fd, void *buf, unsigned long n, int flags);"]
   :kill ["int kill(int pid, int sig);"]
   :waitpid ["int waitpid(int pid, int *status, int options);"]
   :poll ["int poll(rm_pollfd_t *fds, unsigned long n, int timeout);" :rm_pollfd_t]
   :environ ["extern char **environ;"]
   :sysconf ["long sysconf(int name);"]
   :getpid ["int getpid(void);"]
   :fork ["int fork(void);"]
   :_exit ["void _exit(int status);"]
   :mmap ["void *mmap(void *addr, unsigned long length, int prot, int flags, int fd, long offset);"]
   :munmap ["int munmap(void *addr, unsigned long length);"]
   ;; Limits.
   :setrlimit ["int setrlimit(int resource, const rm_rlimit_t *rlim);" :rm_rlimit_t]
   :getrlimit ["int getrlimit(int resource, rm_rlimit_t *rlim);" :rm_rlimit_t]
   :getrusage ["int getrusage(int who, rm_rusage_t *usage);" :rm_rusage_t]
   :prctl ["int prctl(int option, unsigned long a2, unsigned long a3, unsigned long a4, unsigned long a5);"]
   :setsid ["int setsid(void);"]
   ;; Files.
   :open ["int open(const char *path, int flags, int mode);"]
   :write ["long write(int fd, const void *buf, unsigned long n);"]
   :read ["long read(int fd, void *buf, unsigned long n);"]
   :pipe ["int pipe(int fds[2]);"]
   :close ["int close(int fd);"]
   :fsync ["int fsync(int fd);"]
   :fchmod ["int fchmod(int fd, unsigned int mode);"]
   :rename ["int rename(const char *from, const char *to);"]
   :unlink ["int unlink(const char *path);"]
   :mkdir ["int mkdir(const char *path, unsigned int mode);"]
   :rmdir ["int rmdir(const char *path);"]
   :mkdtemp ["char *mkdtemp(char *template);"]
   :realpath ["char *realpath(const char *path, char *resolved);"]
   :readlink ["long readlink(const char *path, char *buf, unsigned long size);"]
   :free ["void free(void *p);"]
   ;; stat is a real symbol from glibc 2.33 on; older ones only have __xstat.
   :stat ["int stat(const char *path, rm_stat_t *buf);" :rm_stat_t]
   :lstat ["int lstat(const char *path, rm_stat_t *buf);" :rm_stat_t]
   :access ["int access(const char *path, int mode);"]
   :isatty ["int isatty(int fd);"]
   ;; The clock and the environment.
   :clock_gettime ["int clock_gettime(int clock, rm_timespec_t *ts);" :rm_timespec_t]
   :nanosleep ["int nanosleep(const rm_timespec_t *req, rm_timespec_t *rem);" :rm_timespec_t]
   :setenv ["int setenv(const char *name, const char *value, int overwrite);"]
   :unsetenv ["int unsetenv(const char *name);"]
   ;; zlib.
   :compressBound ["unsigned long compressBound(unsigned long sourceLen);"]
   :compress2 ["int compress2(uint8_t *dest, unsigned long *destLen, const uint8_t *source, unsigned long sourceLen, int level);"]
   :uncompress ["int uncompress(uint8_t *dest, unsigned long *destLen, const uint8_t *source, unsigned long sourceLen);"]
   :crc32 ["unsigned long crc32(unsigned long crc, const uint8_t *buf, unsigned int len);"]})

(local declared {})

(fn declare-one! [name]
  ;; Declares `name` and what it needs, once per process.
  (when (not (. declared name))
    (tset declared name true)
    (let [[text & needs] (or (. declarations name)
                             (error (.. "libc: no declaration of " name)))]
      (each [_ n (ipairs needs)] (declare-one! n))
      (when text (pcall ffi.cdef text)))))

(fn present? [namespace name]
  (if (= "rm_" (name:sub 1 3))
      (pcall ffi.typeof name)
      (pcall #(. namespace name))))

(fn declare [names ?namespace]
  "Declare the C functions, variables and types named in `names` (each at most once
per process, with the types it needs). Returns `?namespace` (default ffi.C) when all
of them are there, else nil; nil too without LuaJIT's FFI."
  (when ffi
    (each [_ name (ipairs names)] (declare-one! name))
    (let [namespace (or ?namespace ffi.C)]
      (when (accumulate [ok? true _ name (ipairs names)]
              (and ok? (present? namespace name)))
        namespace))))

(fn library [file-names names]
  "The first of the shared libraries `file-names` that loads (ffi.load) and has every
function of `names` (declared here), or nil and a message."
  (if (not ffi) (values nil "no FFI (LuaJIT's) to load a library with")
      (do (each [_ name (ipairs names)] (declare-one! name))
          (var lib nil)
          (var why nil)
          (each [_ file (ipairs file-names) &until lib]
            (let [(ok? l) (pcall ffi.load file)]
              (if (not ok?) (set why l)
                  (declare names l) (set lib l)
                  (set why (.. file " lacks one of " (table.concat names ", "))))))
          (if lib lib (values nil (.. "cannot load " (. file-names 1) ": " (tostring why)))))))

(fn error-text [?code]
  "The C library's message for the error number `?code` (default: the last call's,
errno)."
  ;; errno first: the declaration could make C calls of its own.
  (let [code (or ?code (ffi.errno))]
    (declare [:strerror])
    (ffi.string (ffi.C.strerror code))))

{: ffi : declare : library : error-text}
