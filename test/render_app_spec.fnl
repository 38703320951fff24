;; `love . --render` run headless: the player's still by default, --samples 1 the
;; one-ray picture; no stray "error:" line from the window system; --help and
;; --help-dev. (src/app/render.fnl, src/app/quality.fnl, src/util/runtime-dir.fnl)
(local png (require :src.util.png))
(local runtime-dir (require :src.util.runtime-dir))

(local {: sh : root &as app} (require :test.support.app))

(fn run [args]
  (app.love args))

(fn read [path] (with-open [f (assert (io.open path :rb))] (f:read :*a)))

(describe "love . --render"
  (fn []
    (os.execute "mkdir -p test/out")

    (it "draws the anti-aliased still by default, and the one-ray picture with --samples 1"
      (fn []
        (let [(code out) (run "--render scenes/machined-part.fnl --out test/out/render-still.png --size 160x90")
              (code1 out1) (run "--render scenes/machined-part.fnl --out test/out/render-one.png --size 160x90 --samples 1")
              (coded outd) (run "--render scenes/machined-part.fnl --out test/out/render-draft.png --size 160x90 --quality draft")]
          (assert.are.equal 0 code out)
          (assert.are.equal 0 code1 out1)
          (assert.are.equal 0 coded outd)
          (assert.truthy (out:find "wrote test/out/render-still.png (160x90, adaptive 4 x 4, " 1 true) out)
          (assert.truthy (out1:find "wrote test/out/render-one.png (160x90, one ray a pixel, " 1 true) out1)
          (assert.are.equal (read "test/out/render-one.png") (read "test/out/render-draft.png"))
          (assert.are_not.equal (read "test/out/render-one.png") (read "test/out/render-still.png"))
          (let [img (assert (png.read-file "test/out/render-still.png"))]
            (assert.are.same [160 90] [img.width img.height])))))

    (it "prints no window-system 'error:' line without XDG_RUNTIME_DIR or a display, and leaves no folder"
      (fn []
        (os.execute "rm -rf test/out/runtime-tmp && mkdir -p test/out/runtime-tmp")
        (let [(code out) (sh (.. "env -u XDG_RUNTIME_DIR -u SDL_VIDEODRIVER -u DISPLAY -u WAYLAND_DISPLAY"
                                 " TMPDIR=" root "/test/out/runtime-tmp timeout 600 love . --render"
                                 " scenes/flat.fnl --out test/out/render-xdg.png --size 32x24 --samples 1"))]
          (assert.are.equal 0 code out)
          (assert.falsy (out:find "error" 1 true) out)
          (assert.falsy (out:find "XDG_RUNTIME_DIR" 1 true) out)
          (let [(_ listing) (sh "ls -A test/out/runtime-tmp")]
            (assert.are.equal "" listing)))))

    (it "needs a stand-in XDG_RUNTIME_DIR only when Wayland's library would complain"
      (fn []
        (let [env (fn [t] #(. t $1))]
          (assert.is_true (runtime-dir.needed? (env {})))
          (assert.is_true (runtime-dir.needed? (env {:XDG_RUNTIME_DIR "relative"})))
          (assert.is_false (runtime-dir.needed? (env {:XDG_RUNTIME_DIR "/run/user/1000"})))
          (assert.is_false (runtime-dir.needed? (env {:WAYLAND_DISPLAY "/run/wayland-0"})))
          (assert.is_true (runtime-dir.needed? (env {:WAYLAND_DISPLAY "wayland-0"}))))))

    (it "--help lists the user's modes; --help-dev the internal ones"
      (fn []
        (let [(code out) (run "--help")
              (dcode dout) (run "--help-dev")]
          (assert.are.equal 0 code out)
          (assert.are.equal 0 dcode dout)
          (assert.truthy (out:find "--render SCENE" 1 true) out)
          (assert.truthy (out:find "--quality" 1 true) out)
          (assert.falsy (out:find "--soak" 1 true) out)
          (assert.truthy (dout:find "--soak" 1 true) dout)
          (assert.truthy (dout:find "--warm-shader" 1 true) dout))))))
