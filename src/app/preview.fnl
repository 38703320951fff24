;; A new scene on screen before its shader is compiled (issue 42). A structural edit
;; needs a new shader, and llvmpipe takes 0.3 to 3 s to compile one (a desktop driver
;; up to 10 s); a helper process compiles it while the window goes on (warm.fnl). An
;; interpreter shader that would need no compile is no way out on llvmpipe: it runs
;; every branch of a dispatch, so each tape instruction would cost every kind of node
;; (docs/benchmarks.md). The CPU reference needs no compile: LuaJIT runs the tape's
;; Lua at once. So while the helper compiles, a LÖVE thread draws the new scene with
;; it (src/reference/picture.fnl), small pictures first (16x9, 32x18, then 64x36: the
;; first came 40-240 ms after the edit for the showcase scenes), each shown as soon as
;; it is drawn, until the shader is ready. The reference is what the shader is checked against pixel by
;; pixel, so the preview shows the state the shader then draws, at a lower resolution.
;;
;; The thread lives as long as the player (started at the first request); jobs and
;; pictures travel as wire bytes over LÖVE channels, and a job runs only while the
;; `wanted` channel holds its id.

(local wire (require :src.util.wire))
(local picture (require :src.reference.picture))

;; The largest preview picture: 64x36 on a 16:9 window. The next rung, 128x72, took
;; 0.1 to 3.8 s (four times the one before) on this 2-core machine, beside the helper's
;; compile: with it, the shader's picture came 11% later (median of the eight showcase
;; scenes' structural edits, one interleaved run), for a preview shown some 0.3 s.
(local max-pixels 2400)
;; The thread holds its own copy of the scene (and builds its own plan): not for a
;; scene of more objects than this (asked before encoding it: encoding a million
;; spheres, 160 MB on the wire, took the player to 2.1 GB), nor of more bytes on the
;; wire than that.
(local max-objects 50000)
(local max-scene-bytes (* 8 1024 1024))

(fn new []
  "A previewer with no thread yet (started by the first request)."
  {:thread nil :jobs nil :results nil :wanted nil :id 0 :latest nil :error nil :failed nil})

(fn start! [pv]
  (let [thread (love.thread.newThread "src/app/preview-thread.lua")]
    (set pv.jobs (love.thread.newChannel))
    (set pv.results (love.thread.newChannel))
    (set pv.wanted (love.thread.newChannel))
    (thread:start pv.jobs pv.results pv.wanted)
    (set pv.thread thread)))

(fn prepare! [pv]
  "Start the thread now (the player's start): it loads its modules while nothing
waits for it, so the first edit's preview does not pay for that (about 0.2 s)."
  (when (not pv.thread) (start! pv)))

(fn set-wanted! [pv id]
  (pv.wanted:performAtomic (fn [c] (c:clear) (c:push id))))

(fn request! [pv scene options cam aspect ?max-pixels]
  "Start drawing `scene` (plan `options` as plan.scene->plan takes them) seen by `cam`
for a window of `aspect` (width / height), cancelling any earlier request; pictures
of `?max-pixels` at most (default max-pixels). The request's id, or nil and the
reason there is no preview."
  (if pv.failed (values nil pv.failed)
      (> (length (or scene.objects [])) max-objects)
      (values nil (.. "a scene of more than " max-objects " objects is not previewed"))
      (case (wire.encode {:id (+ pv.id 1) : scene : options :cam cam
                          :sizes (picture.ladder aspect (or ?max-pixels max-pixels))})
        (nil err) (values nil err)
        bytes (if (> (length bytes) max-scene-bytes)
                  (values nil (.. "a scene of more than " max-scene-bytes " bytes is not previewed"))
                  (do (when (not pv.thread) (start! pv))
                      (set pv.id (+ pv.id 1))
                      (set pv.latest nil)
                      (set pv.error nil)
                      (set-wanted! pv pv.id)
                      (pv.jobs:push bytes)
                      pv.id)))))

(fn cancel! [pv]
  "No preview is wanted any more: the thread stops the one it draws."
  (set pv.latest nil)
  (when pv.thread (set-wanted! pv 0)))

(fn poll! [pv]
  "The newest picture of the request in force: {:id :w :h :image :bytes (its RGBA
bytes, rows from the top) :seconds (the drawing's)}, or nil. A job that failed says
why in pv.error; a thread that died, in pv.failed, and no preview is asked of it
again."
  (when pv.thread
    (var message (pv.results:pop))
    (while message
      (case (wire.decode message)
        ;; A job that failed (its scene's plan, the reference on it) leaves no
        ;; picture; the next edit asks again.
        result (if result.error
                   (when (= result.id pv.id) (set pv.error (.. "preview: " result.error)))
                   (= result.id pv.id)
                   (let [data (love.image.newImageData result.w result.h :rgba8 result.bytes)
                         image (love.graphics.newImage data)]
                     (data:release)
                     (image:setFilter :linear :linear)
                     (when pv.latest (pv.latest.image:release))
                     (set pv.latest {:id result.id :w result.w :h result.h : image
                                     :bytes result.bytes :seconds result.seconds}))))
      (set message (pv.results:pop)))
    (case (pv.thread:getError)
      err (set pv.failed (.. "preview thread: " err))))
  pv.latest)

(fn stop! [pv]
  "End the thread (the player quits)."
  (when pv.thread
    (set-wanted! pv 0)
    (pv.jobs:push "quit")))

{: new : prepare! : request! : cancel! : poll! : stop! : max-pixels}
