;; The shader chunks (shaders/): GLSL files read once, whose `// @slot NAME` lines
;; and `@{NAME}` names the generators fill (src/render/codegen.fnl, the drawing
;; strategies in src/sdf/strategies/), and whose `// @part NAME` lines split one file
;; into parts taken one at a time.

;; `pairs` under another name: a loop over `pairs` by that name is LuaJIT's ITERN,
;; which Debian 12's LuaJIT ends early once despecialised (see src/util/wire.fnl).
(local each-pair pairs)

(local files (require :src.util.files))

;; Chunks are read through the program's one file reader (project files, from any
;; working directory); tests may swap the reader. Chunks are cached by path. A chunk
;; that cannot be read stops generation with a message (see `shader`).
(local state {:read files.read-project :cache {}})

;; Errors raised by `chunk` carry this marker, so `shader` returns them as messages.
(local chunk-error {})

(fn set-reader! [read]
  "Read shader chunks with `read` (path -> text, or nil and a message) from now on,
and forget cached ones."
  (set state.read read)
  (set state.cache {}))

(fn chunk [path]
  (when (= nil (. state.cache path))
    (case (state.read path)
      text (tset state.cache path text)
      (nil err) (error {:marker chunk-error :message (tostring (or err (.. "cannot read " path)))})))
  (. state.cache path))

;;; Lines: a chunk's text becomes a list of lines; `// @slot NAME` lines are replaced
;;; by the slot's lines at the same indentation. Nested lists flatten.

(fn flatten-into [out indent lines]
  ;; A uniform's declaration (emit-glsl.declare) stays an item of its own.
  (each [_ line (ipairs lines)]
    (if (and (= (type line) :table) line.declare) (table.insert out line)
        (= (type line) :table) (flatten-into out indent line)
        (table.insert out (if (= line "") "" (.. indent line))))))

(fn chunk-declaration [line]
  ;; A chunk's `uniform TYPE uName;` line as a declaration (emit-glsl.declare's
  ;; data): chunks declare their uniforms so, and codegen places them (load-once).
  (let [(ty name count trailer) (line:match "^uniform (%w+) (u[%w_]+)%[?(%d*)%]?;(.*)$")]
    (when name
      {:declare {:type ty : name :count (tonumber count) : trailer :text line}})))

(fn fill-names [path line slots]
  ;; `line` of chunk `path` with each `@{NAME}` written as the name `slots` gives it
  ;; (a string: the function a chunk defines or calls, chosen by the plan).
  (if (not (line:find "@{" 1 true)) line
      (pick-values 1 (line:gsub "@{([%w%-]+)}"
                                (fn [name]
                                  (let [v (. slots name)]
                                    (assert (= (type v) :string)
                                            (.. path ": no name given for @{" name "}"))
                                    v))))))

(fn fill-lines [path lines slots]
  ;; `lines` (of chunk `path`) with their slots filled: see `fill`.
  (let [out []]
    (each [_ line (ipairs lines)]
      (let [(indent name) (line:match "^(%s*)// @slot ([%w%-]+)%s*$")]
        (if name
            (let [given (. slots name)]
              (assert (= (type given) :table) (.. path ": no lines given for slot " name))
              (flatten-into out indent given))
            (table.insert out (or (chunk-declaration line) (fill-names path line slots))))))
    out))

(fn fill [path slots]
  "Lines of chunk `path` with its slots filled from `slots`: a `// @slot NAME` line
by the lines `slots` gives for NAME, an `@{NAME}` in a line by the name (a string)
it gives. The chunk's own text declares both; nothing generated is rewritten."
  (let [out (fill-lines path (icollect [line (: (.. (chunk path) "\n") :gmatch "([^\n]*)\n")] line)
                        slots)]
    ;; A chunk file ends with a newline; do not keep the empty last line.
    (when (= (. out (length out)) "") (table.remove out))
    out))

(fn parts [path]
  "The parts of chunk `path`, split at `// @part NAME` lines: name -> lines (the
comment lines before the first part are the chunk's own documentation)."
  (let [out {}]
    (var current nil)
    (each [line (: (.. (chunk path) "\n") :gmatch "([^\n]*)\n")]
      (let [name (line:match "^// @part ([%w%-]+)%s*$")]
        (if name (do (set current []) (tset out name current))
            current (table.insert current line))))
    ;; A blank line that only separates one part from the next is not the part's.
    (each [_ lines (each-pair out)]
      (while (= (. lines (length lines)) "") (table.remove lines)))
    out))

(fn fill-part [path name slots]
  "Lines of part `name` of chunk `path` (see `parts`), slots filled as `fill` does."
  (let [lines (. (parts path) name)]
    (assert lines (.. path ": no part " name))
    (fill-lines path lines slots)))

(fn chunk-error? [e]
  "Whether `e`, an error raised while chunks were filled, is a chunk that could not be
read (its :message says which)."
  (and (= (type e) :table) (= e.marker chunk-error)))

{: set-reader! : chunk : flatten-into : fill : parts : fill-part : chunk-error?}
