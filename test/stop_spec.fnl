;; SIGTERM during the long command-line modes (src/app/stop.fnl): --mesh, --render and
;; --record stop, exit 1 with a message and write no partial file. The signal is sent
;; once the command's progress shows (so it is at work, whatever the machine's speed);
;; a KILL 120 s later, which the verdict would show as exit 137, only catches a TERM
;; not heeded.
(fn sh [command]
  (with-open [p (io.popen command)] (p:read "*a")))

(fn term-when [command progress err-file]
  "Run `command` (its stderr to `err-file`), send it SIGTERM once `progress` is in
that file; its exit code and stderr."
  (let [out (sh (.. "SDL_VIDEODRIVER=offscreen " command " 2>" err-file " & p=$!; "
                    "for i in $(seq 1 3000); do grep -q '" progress "' " err-file " && break; sleep 0.1; done; "
                    "kill -TERM $p; (sleep 120; kill -KILL $p) >/dev/null 2>&1 & w=$!; "
                    "wait $p; echo \"rc=$?\"; kill $w 2>/dev/null"))
        err (sh (.. "cat " err-file))]
    (values (tonumber (out:match "rc=(%d+)")) err)))

(fn exists? [path]
  (case (io.open path :rb) f (do (f:close) true) _ false))

(describe "SIGTERM stops a long command"
  (fn []
    (os.execute "rm -rf test/out/stop && mkdir -p test/out/stop")

    (it "--mesh: exit 1, 'nothing written', no file"
      (fn []
        (let [(rc err) (term-when "love . --mesh scenes/machined-part.fnl --out test/out/stop/m.stl --resolution 384"
                                  "mesh:" "test/out/stop/mesh.err")]
          (assert.are.equal 1 rc err)
          (assert.truthy (err:find "error: scenes/machined-part.fnl: stopped (SIGINT or SIGTERM); nothing written" 1 true) err)
          (assert.is_false (exists? "test/out/stop/m.stl")))))

    (it "--render: exit 1, 'nothing written', no file"
      (fn []
        (let [(rc err) (term-when "love . --render scenes/flower.fnl --out test/out/stop/r.png --size 1280x720 --quality final --samples 8"
                                  "render 1280x720" "test/out/stop/render.err")]
          (assert.are.equal 1 rc err)
          (assert.truthy (err:find "error: --render: stopped (SIGINT or SIGTERM); nothing written" 1 true) err)
          (assert.is_false (exists? "test/out/stop/r.png")))))

    (it "--record: exit 1, the frames written before kept"
      (fn []
        (let [(rc err) (term-when "love . --record scenes/melt.fnl --out test/out/stop/rec --frames 2000 --size 160x90 --samples 1"
                                  "frame 2/" "test/out/stop/record.err")]
          (assert.are.equal 1 rc err)
          (assert.truthy (err:find "error: --record: stopped (SIGINT or SIGTERM); the frames written before are kept" 1 true) err)
          (assert.is_true (exists? "test/out/stop/rec/frame-0001.png"))
          (assert.is_false (exists? "test/out/stop/rec/frame-2000.png")))))))

;; ^C in the player's terminal: SIGINT, which SDL turns into a quit event. The player's
;; compile helpers used to run under os.execute (C's system()), which ignores SIGINT
;; in the whole process while its command runs: with a helper alive, ^C did nothing.
;; The player is started with SIGINT at its default (a shell gives a background job
;; SIGINT ignored; env resets it), sent SIGINT once its still is drawn (its helpers
;; are alive then), and must be gone within 30 s (a KILL after that shows as 137).
(describe "SIGINT stops the player"
  (fn []
    (it "while its compile helpers run"
      (fn []
        (os.execute "mkdir -p test/out/stop")
        (let [log "test/out/stop/player.log"
              out (sh (.. "SDL_VIDEODRIVER=offscreen env --default-signal=INT love . scenes/seed.fnl > " log " 2>&1 & p=$!; "
                          "for i in $(seq 1 3000); do grep -q 'anti-aliased still' " log " && break; sleep 0.1; done; "
                          "sleep 1; grep -c warm-server /proc/[0-9]*/cmdline 2>/dev/null | grep -c ':[1-9]'; "
                          "kill -INT $p; (sleep 30; kill -KILL $p) >/dev/null 2>&1 & w=$!; "
                          "wait $p; echo \"rc=$?\"; kill $w 2>/dev/null"))
              text (sh (.. "cat " log))]
          (assert.truthy (text:find "anti-aliased still" 1 true) text)
          ;; Its helpers were alive when the signal came (the grep counts processes
          ;; whose command line names --warm-server: the helpers and their shells).
          (assert.is_true (>= (tonumber (out:match "^(%d+)")) 1) out)
          (assert.are.equal "0" (out:match "rc=(%d+)") out))))))
