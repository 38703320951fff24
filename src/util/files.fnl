;; The one file reader of the program. Two kinds of file:
;; - project files (shader chunks): read relative to the project's root, through
;;   love.filesystem inside LÖVE (so `love /path/to/project` works from any working
;;   directory) and through io elsewhere, relative to the folder this module was
;;   loaded from;
;; - user files (scenes): a path relative to the working directory, read at most up to
;;   a byte limit, then (inside LÖVE) the bundled file of the same name.
;; Failures are `nil, message`; nothing here raises.

(fn love-filesystem []
  (let [love (rawget _G :love)]
    (and (= (type love) :table) love.filesystem love.filesystem.read love.filesystem)))

(fn module-root []
  ;; "@./src/util/files.fnl" or "@/abs/path/src/util/files.fnl" -> the part before src/.
  (let [info (debug.getinfo 1 :S)
        source (or (and info info.source) "")]
    (or (source:match "^@(.-)src/util/files%.fnl$") "")))

(local root (module-root))

(local filestat (require :src.util.filestat))

;; Files that io.open would wait on (a FIFO with no writer blocks forever) or that
;; hold no text: refused before they are opened.
(local unreadable {:fifo "it is a FIFO (a named pipe), not a file"
                   :socket "it is a socket, not a file"})

(fn read-opened [path ?max-bytes]
  (case (io.open path :rb)
    f (let [(s err) (f:read (or ?max-bytes :*a))]
        (f:close)
        (if s s
            (and err (err:find "directory")) (values nil "it is a directory")
            err (values nil err)
            ""))
    (nil err) (values nil err)))

(fn read-io [path ?max-bytes]
  (case (. unreadable (?. (filestat.stat path) :type))
    why (values nil why)
    _ (read-opened path ?max-bytes)))

(fn read-project [path]
  "The text of project file `path` (relative to the project root, e.g.
\"shaders/pipeline/map.glsl\"), or nil and a message naming the path."
  (let [lfs (love-filesystem)]
    (case (if lfs
              (let [(ok? text) (pcall lfs.read path)]
                (if (and ok? text) text (values nil "not found in the project")))
              (read-io (.. root path)))
      text text
      (nil err) (values nil (.. path ": cannot read a project file: " (tostring err))))))

(fn read-user [path ?max-bytes]
  "The text of user file `path` (relative to the working directory), at most
`?max-bytes` bytes; inside LÖVE a path that is not found there is looked up among the
project's own files (the bundled scenes). A directory is refused. Returns the text, or
nil and a message without the path (the caller names the file)."
  (case (read-io path ?max-bytes)
    text text
    (nil err) (let [lfs (love-filesystem)
                    ;; Not for a directory ("No such file or directory" is a missing file).
                    info (and lfs lfs.getInfo (not= err "it is a directory")
                              (lfs.getInfo path :file))]
                (if info
                    (lfs.read path ?max-bytes)
                    (values nil err)))))

(fn list-project [dir]
  "Names of the files in project folder `dir` (e.g. \"src/sdf/primitives\"), sorted,
or nil and a message."
  (let [lfs (love-filesystem)]
    (if lfs
        (let [items (lfs.getDirectoryItems dir)]
          (if (= (length items) 0)
              (values nil (.. dir ": no such project folder, or it is empty"))
              (doto items table.sort)))
        (case (pcall require :lfs)
          (true fs) (case (pcall #(icollect [name (fs.dir (.. root dir))]
                                    (when (not (name:match "^%.")) name)))
                      (true out) (doto out table.sort)
                      (_ err) (values nil (.. dir ": " (tostring err))))
          _ (values nil "listing a folder needs LuaFileSystem (lua-filesystem)")))))

{: read-project : read-user : list-project}
