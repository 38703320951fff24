;; Compile time of generated shaders against hand-written ones (issue 42):
;;   luajit tools/fnl.lua tools/compile-time.fnl [--rounds N] [--size WxH] [--out DIR]
;;                        [--dump-only] ITEM...
;; ITEM: SCENE (the shader the player compiles, values in uniforms), SCENE:fold (values
;; folded into the code: --render, --record, --export-shader), PORT.glsl@SCENE (a
;; hand-written shader drawn with SCENE's uniforms), or a dump (.lua) that this tool
;; or tools/ab-dump.fnl wrote, from any checkout (so before and after can be timed in
;; one interleaved run: run this with --dump-only in the other checkout's directory).
;; Each item is written to DIR (default /tmp/compile-time) as a dump, its size printed
;; (lines of GLSL, and lines after inlining every call from the entry point, which is
;; what Mesa's compiler works on: it inlines every call), and then, unless
;; --dump-only, all are timed in turn by tools/compile-run under LÖVE with
;; MESA_SHADER_CACHE_DISABLE=true and SDL_VIDEODRIVER=offscreen: newShader plus the
;; first draw at 16x16 (llvmpipe compiles at the first draw), N rounds (default 5),
;; medians.
(local load (require :src.scene.load))
(local plan (require :src.render.plan))
(local codegen (require :src.render.codegen))
(local uniforms (require :src.render.uniforms))
(local camera (require :src.render.camera))

(fn read-text [path]
  "The contents of the file at `path`, or an error."
  (let [f (assert (io.open path :r))
        s (f:read :*a)]
    (f:close)
    s))

(fn code-line? [line]
  "Whether a GLSL line holds code (not blank, not only a comment, not a lone brace)."
  (let [s (line:gsub "//.*$" "")]
    (not= nil (s:match "[^%s{}]"))))

(fn functions-of [source]
  "The functions of a GLSL text: name -> {:lines n :body text} (n: lines of code in the
body), for functions whose definition starts at column 0 and ends at a `}` there."
  (let [fns {}]
    (var current nil)
    (each [line (source:gmatch "[^\n]*")]
      (if current
          (if (line:match "^}")
              (set current nil)
              (do (when (code-line? line) (set current.lines (+ current.lines 1)))
                  (table.insert current.body line)))
          (let [name (line:match "^[%w_]+%s+([%w_]+)%s*%(")]
            (when (and name (not (line:match ";%s*$")))
              (set current {:lines 0 :body []})
              (tset fns name current)))))
    (each [_ f (pairs fns)] (set f.body (table.concat f.body "\n")))
    fns))

(fn inlined-size [fns root]
  "Lines of code of `root` with every call inlined (each call site a copy), and how
many copies of each function that makes: a table name -> copies. 0 and none when
the text has no function `root`."
  (let [memo {}
        copies {}]
    (fn size [name stack]
      (or (. memo name)
          (let [f (or (. fns name) {:lines 0 :body ""})]
            (var n f.lines)
            (each [callee (f.body:gmatch "([%a_][%w_]*)%s*%(")]
              (when (and (. fns callee) (not= callee name) (not (. stack callee)))
                (tset stack name true)
                (set n (+ n (size callee stack)))
                (tset stack name nil)))
            (tset memo name n)
            n)))
    (fn count [name times]
      (tset copies name (+ (or (. copies name) 0) times))
      (each [callee (: (or (?. fns name :body) "") :gmatch "([%a_][%w_]*)%s*%(")]
        (when (and (. fns callee) (not= callee name))
          (count callee times))))
    (let [total (size root {})]
      (count root 1)
      (values total copies))))

(fn scene-dump [scene-path fold?]
  "The source and packed uniforms of a scene's shader (LÖVE's, as on llvmpipe)."
  (let [scene (assert (load.load-file scene-path))
        p (assert (plan.scene->plan scene (plan.renderer-options "llvmpipe" {:fold? fold?})))]
    {:source (assert (codegen.shader p :love))
     :uniforms (uniforms.pack scene p (camera.from-scene scene) 16 16)}))

(fn write-dump [path {: source :uniforms us}]
  "Write a dump as tools/ab-dump.fnl does: a Lua file returning source and uniforms."
  (let [f (assert (io.open path :w))]
    (f:write "return {source=[==[" source "]==], uniforms={\n")
    (each [_ u (ipairs us)]
      (f:write "{name=\"" u.name "\", type=\"" u.type "\"")
      (when u.values
        (f:write ", values={" (table.concat (icollect [_ v (ipairs u.values)] (string.format "%.17g" v)) ",") "}"))
      (when u.texture
        (f:write ", texture={width=" u.texture.width ", height=" u.texture.height ", data={"
                 (table.concat (icollect [_ v (ipairs u.texture.data)] (string.format "%.9g" v)) ",") "}}"))
      (f:write "},\n"))
    (f:write "}}\n")
    (f:close)))

(fn item-dump [item]
  "The dump of one command-line item, and a short name for it."
  (let [(port scene) (item:match "^(.-)@(.+)$")
        (scene-path form) (item:match "^(.-):(fold)$")]
    (if (item:match "%.lua$") (values (dofile item) (item:match "([^/]+)%.lua$"))
        port (values {:source (read-text port) :uniforms (. (scene-dump scene false) :uniforms)}
                     (port:match "([^/]+)%.glsl$"))
        scene-path (values (scene-dump scene-path true) (.. (scene-path:match "([^/]+)%.fnl$") "-folded"))
        (values (scene-dump item false) (item:match "([^/]+)%.fnl$")))))

(fn main [args]
  (let [o {:rounds 5 :w 16 :h 16 :out "/tmp/compile-time" :items []}]
    (var i 1)
    (while (<= i (length args))
      (case (. args i)
        :--rounds (do (set o.rounds (tonumber (. args (+ i 1)))) (set i (+ i 1)))
        :--size (let [(w h) (: (. args (+ i 1)) :match "^(%d+)x(%d+)$")]
                  (set o.w (tonumber w)) (set o.h (tonumber h)) (set i (+ i 1)))
        :--out (do (set o.out (. args (+ i 1))) (set i (+ i 1)))
        :--dump-only (set o.dump-only? true)
        item (table.insert o.items item))
      (set i (+ i 1)))
    (os.execute (.. "mkdir -p '" o.out "'"))
    (let [paths (icollect [_ item (ipairs o.items)]
                  (let [(dump name) (item-dump item)
                        path (if (item:match "%.lua$") item (.. o.out "/" name ".lua"))
                        fns (functions-of dump.source)
                        (total copies) (inlined-size fns :effect)
                        maps (icollect [_ m (ipairs [:map :mapColor :mapObject :mapOthers :mapFinite
                                                     :objects :material :mapScene])]
                               (when (. copies m) (.. m " " (. copies m))))]
                    (when (not (item:match "%.lua$")) (write-dump path dump))
                    (print (string.format "size %s: %d lines of GLSL, %d lines inlined; copies: %s"
                                          name (select 2 (dump.source:gsub "\n" "\n")) total
                                          (table.concat maps ", ")))
                    path))]
      (when (not o.dump-only?)
        (let [here (or (os.getenv :COMPILE_TIME_HOME) ".")]
          (os.execute (string.format "MESA_SHADER_CACHE_DISABLE=true SDL_VIDEODRIVER=offscreen love '%s/tools/compile-run' %d %d %d %s"
                                     here o.rounds o.w o.h
                                     (table.concat (icollect [_ p (ipairs paths)] (.. "'" p "'")) " "))))))))

(main [...])
