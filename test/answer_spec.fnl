;; tier: fast
;; Answers from a subverted scene worker (src/scene/answer.fnl, src/scene/worker.fnl):
;; code that escaped the sandbox in the worker, or another program in its place, may
;; answer anything the wire carries. Each forged answer ends in a message that names
;; the field, never an internal error, and the worker that sent it is stopped. Pure:
;; the stand-in worker is test/fixtures/worker/fake.fnl under plain LuaJIT.
(local worker (require :src.scene.worker))
(local answer (require :src.scene.answer))
(local wire (require :src.util.wire))
(local filestat (require :src.util.filestat))
(local handle (. (require :src.scene.worker-main) :handle))

(local file "x.fnl")
(local prefix "x.fnl: the scene worker's answer was refused: ")

;; Scenes with code (a file of plain data never reaches the worker).
(local spheres "(let [r 1] {:objects [{:kind :sphere :pos [0 0 1] :radius r}
                                      {:kind :box :pos [2 0 1] :size [1 1 1]}
                                      {:kind :sphere :pos [0 3 1] :radius 2}]})")
(local tree "(let [r 1] {:objects [{:kind :union :children [{:kind :sphere :radius r}
                                                            {:kind :torus :pos [0 0 2]}]}]})")
(local animated "(let [r 1] {:lighting {:model :modern}
                             :objects [{:kind :sphere :radius (fn [t] (+ 1 t))
                                        :color (fn [t] [0.5 0.5 (/ t 10)])}]})")
(local with-custom
  (with-open [f (assert (io.open "scenes/custom.fnl"))] (f:read :*a)))

(fn real-answer [source]
  ;; What the worker answers for `source` (its own handler, in this process).
  (let [a (handle {:op :load : source : file})]
    (assert a.ok a.message)
    a))

(fn forged [source f]
  ;; The worker's answer for `source`, changed by `f` (which may return another).
  (let [a (real-answer source)]
    (or (f a) a)))

(fn copy [a]
  (wire.decode (assert (wire.encode a))))

(fn check [a]
  ;; The check of answer `a` (a copy: the check takes it apart): nil and message.
  (answer.check-scene (copy a) file "source"))

(fn nested [depth leaf]
  ;; A node tree `depth` unions deep.
  (var node leaf)
  (for [_ 1 depth] (set node {:kind :union :children [node]}))
  node)

(fn write-temp [bytes]
  (let [path (os.tmpname)]
    (with-open [f (assert (io.open path :wb))] (f:write bytes))
    path))

(fn timed [f]
  (let [t0 (filestat.monotonic)
        (a b) (f)]
    (values (- (filestat.monotonic) t0) a b)))

(fn with-fake [mode bytes f]
  (let [path (write-temp bytes)]
    (worker.kill!)
    (worker.set-command! ["luajit" "tools/fnl.lua" "test/fixtures/worker/fake.fnl" mode path])
    (let [(ok? err) (pcall f)]
      (worker.kill!)
      (worker.set-command! nil)
      (os.remove path)
      (when (not ok?) (error err 0)))))

(fn refused-within [bytes source seconds]
  ;; The message of a load of `source` whose answer is `bytes`, within `seconds`.
  (var msg nil)
  (with-fake :forged bytes
    #(let [(t scene err) (timed #(worker.load-source source file))]
       (assert.is_nil scene)
       (assert.is_true (< t seconds) (.. "took " t " s"))
       (set msg err)))
  msg)

(fn refused? [msg]
  ;; A message of the check: the prefix, no internal error or traceback.
  (and (= (type msg) :string) (= prefix (msg:sub 1 (length prefix)))
       (not (msg:find "traceback" 1 true)) (not (msg:find "%.fnl:%d+: in ")) (not (msg:find "%.lua:%d+:"))))

(describe "the main process's check of the scene worker's answers"
  (fn []
    (it "takes the worker's answer for each scene as the loader gives it here"
      (fn []
        (each [_ src (ipairs [spheres tree animated with-custom])]
          (let [(scene err) (check (real-answer src))]
            (assert.is_truthy scene err)
            (assert.are.equal file scene.file)))))

    (it "refuses forged kinds, counts, numbers, sizes and strings, naming the field"
      (fn []
        (let [nan (/ 0 0)
              cases
              [[spheres #(set (. $.scene.objects 1 :kind) :blob)
                "objects[1].kind: unknown kind :blob (`love . --kinds` lists them all)"]
               [spheres #(set (. $.scene.objects 1 :radius) nan)
                "objects[1].radius: must be a positive number from 1e-6 to 1e7, got nan"]
               [spheres #(set (. $.scene.objects 3 :radius) math.huge)
                "objects[3].radius: must be a positive number from 1e-6 to 1e7, got inf"]
               [spheres #(set (. $.scene.objects 1 :radius) 1e308)
                "objects[1].radius: must be a positive number from 1e-6 to 1e7, got 1e+308"]
               [spheres #(set (. $.scene.objects 2 :size) [1 -1 1])
                "objects[2].size[2]: must be a positive number from 1e-6 to 1e7, got -1"]
               [spheres #(set (. $.scene.objects 1 :radius) "1")
                "objects[1].radius: must be a positive number from 1e-6 to 1e7, got \"1\""]
               [spheres #(set (. $.scene.objects 1 :pos) [0 0 (- math.huge)])
                "objects[1].pos[3]: must be a number from -1e7 to 1e7, got -inf"]
               [spheres #(set (. $.scene.objects 1 :pos) (fcollect [i 1 100000] i))
                "objects[1].pos: must be a list of three numbers like [1 2 3], got a list of 100000 items"]
               [spheres #(tset $.scene.objects 1000000000 (. $.scene.objects 1))
                "objects: has 1000000000 objects; at most 1000000 are allowed (remove 999000000)"]
               [spheres #(set (. $.scene.objects 2 :index) 7) "objects[2].index: must be 2"]
               [spheres #(set (. $.scene.objects 1 :extra) 1)
                "objects[1].extra: unknown field; known fields: :color :emission :kind :mirror :pos :radius :rotate :roughness :scale"]
               [spheres #(set $.scene.render.max-steps 1e9)
                "render.max-steps: must be an integer from 1 to 100000, got 1000000000"]
               [spheres #(set $.scene.camera.fov nan)
                "camera.fov: must be a number of degrees from 0.1 to 179, got nan"]
               [spheres #(set $.scene.name (string.rep "x" 1000))
                "name: must be a line of UTF-8 text of at most 80 bytes, got a string of 1000 bytes"]
               [spheres #(set $.scene.name "\27[31mred")
                "name: must be a line of UTF-8 text of at most 80 bytes, got \"\\027[31mred\""]
               [spheres #(set $.scene.file "y.fnl") "file: not the file that was sent"]
               [spheres #(set $.scene.objects "many") "objects: not a list"]
               [spheres #(do nil [:a])  "the scene is not a table"]
               [tree #(set (. $.scene.objects 1 :tree :children 2 :kind) 12)
                "objects[1].children[2].kind: must be a kind name like :sphere, got 12"]
               [tree #(set (. $.scene.objects 1 :tree :children) [])
                "objects[1].children: must be a list of 1 or more nodes, got an empty table"]
               [tree #(set (. $.scene.objects 1 :tree :children 1 :radius) -2)
                "objects[1].children[1].radius: must be a positive number from 1e-6 to 1e7, got -2"]
               [tree #(set (. $.scene.objects 1 :tree) (nested 45 {:kind :sphere}))
                "objects[1].children[1].children[1].children[1].chi ... .children[1].children[1].children[1].children[1].children[1]: nested deeper than 32 nodes"]]]
          (each [_ [src f want] (ipairs cases)]
            (let [a (forged src f)
                  (scene msg) (if (= (type a.scene) :table) (check a)
                                  (answer.check-scene a file "source"))]
              (assert.is_nil scene)
              (assert.is_true (refused? msg) msg)
              (assert.are.equal (.. prefix want) msg))))))

    (it "refuses a custom node's forged texts and numbers"
      (fn []
        (let [node #(. (icollect [_ o (ipairs $.scene.objects)] (when (= (?. o :tree :kind) :custom) o.tree)) 1)
              cases
              [[#(tset (node $) :custom :lua "os.exit(1)")
                "its Lua is not the translator's (refused)"]
               [#(tset (node $) :custom :glsl "float sdCustom1(vec3 p) { discard; }")
                "its GLSL is not the translator's (refused)"]
               [#(tset (node $) :custom :glsl (.. (. (node $) :custom :glsl) " "))
                "its digest does not match its GLSL (refused)"]
               [#(tset (node $) :custom :cost (/ 0 0))
                "its cost is not a number from 0 to"]
               [#(tset (node $) :custom "text") "its data is not a translation (refused)"]
               [#(tset (node $) :lipschitz 0) ".lipschitz: must be a positive number"]
               ;; The gyroid shell's factor is 1.9: forged 0.01, the shader's steps
               ;; would be 190 times too long.
               [#(tset (node $) :custom :measured 0.01)
                "a custom node: its measured factor 0.01 is below the slope "]]]
          (each [_ [f want] (ipairs cases)]
            (let [(scene msg) (check (forged with-custom f))]
              (assert.is_nil scene)
              (assert.is_true (refused? msg) msg)
              (assert.is_truthy (msg:find want 1 true) msg))))))

    (it "checks a custom node's measured factor once, not again at each load of a drag"
      (fn []
        ;; A drag loads the scene again at every move (scenes/custom.fnl: 11 ms of the
        ;; app's CPU a move, 56 with the check repeated).
        (let [custom (require :src.sdf.custom)
              measure custom.measure
              calls {:n 0}]
          (set custom.measure (fn [...] (set calls.n (+ calls.n 1)) (measure ...)))
          (let [(ok? err) (pcall #(do (assert (check (real-answer with-custom)))
                                      (set calls.n 0)
                                      (assert (check (real-answer with-custom)))))]
            (set custom.measure measure)
            (assert.is_true ok? (tostring err))
            (assert.are.equal 0 calls.n)))))

    (it "refuses forged functions of time and forged values for them"
      (fn []
        (let [a (real-answer animated)]
          (assert.are.equal 2 (length a.animated))
          (each [_ [f want]
                 (ipairs [[#(set $.animated [[:render :max-steps] [:objects 1 :color]])
                           "render.max-steps: cannot be a function of time"]
                          [#(set $.animated [[:objects 1 :radius] [:objects 1 :radius]])
                           "animated[2]: objects[1].radius is not a value of the scene"]
                          [#(set $.animated [[:objects 9 :radius]])
                           "animated[1]: objects[9].radius is not a value of the scene"]
                          [#(set $.animated [(fcollect [_ 1 200] :objects)])
                           "animated[1]: not the path of a field"]
                          [#(set $.animated [[:objects 1 :color] [:objects 1 :radius]])
                           "animated: not the scene's functions of time, in order"]])]
            (let [(scene msg) (check (forged animated f))]
              (assert.is_nil scene)
              (assert.is_true (refused? msg) msg)
              (assert.is_truthy (msg:find want 1 true) msg)))
          (let [scene (assert (check a))]
            (assert.are.same [2 [0.5 0.5 0.1]] (assert (answer.check-values scene [2 [0.5 0.5 0.1]])))
            (each [_ [vals want]
                   (ipairs [[[2] "the values of the functions of time: not a list of 2"]
                            [[2 [0.5 0.5 0.1] 3] "the values of the functions of time: not a list of 2"]
                            [[(/ 0 0) [0.5 0.5 0.1]] "objects[1].radius: must be a positive number from 1e-6 to 1e7, got nan"]
                            [[1 [0.5 0.5 2]] "objects[1].color[3]: must be a colour of three numbers from 0 to 1, got 2"]
                            [[1 "red"] "objects[1].color: must be a colour of three numbers from 0 to 1, got \"red\""]])]
              (let [(ok? msg) (answer.check-values scene vals)]
                (assert.is_nil ok?)
                (assert.is_true (refused? msg) msg)
                (assert.are.equal (.. prefix want) msg)))))))

    (it "refuses forged parameters"
      (fn []
        (let [src "(let [r (param :r 1 {:min 0.5 :max 2})] {:objects [{:kind :sphere :radius r}]})"
              a (real-answer src)]
          (assert.is_truthy (check a))
          (each [_ [f want]
                 (ipairs [[#(set (. $.scene.params 1 :value) 9) "params[1].value: not a value of the parameter"]
                          [#(set (. $.scene.params 1 :max) (/ 0 0)) "params[1]: (param :r ...): a number parameter needs {:min A :max B}"]
                          [#(set (. $.scene.params 1 :kind) :switch) "params[1].kind: not the kind of its value"]
                          [#(set (. $.scene.params 1 :name) "\27]0;x") "params[1]: (param ...): the first argument is the parameter's name"]
                          [#(set $.scene.params (fcollect [_ 1 100] (. $.scene.params 1))) "params[2].kind"]])]
            (let [(scene msg) (check (forged src f))]
              (assert.is_nil scene)
              (assert.is_true (refused? msg) msg)
              (assert.is_truthy (msg:find want 1 true) msg))))))

    (it "ends each forged answer from a worker in a message, and starts a new worker after"
      (fn []
        (let [deep (.. "SDW1 2 2 20005\n2:ok5:scene" (string.rep "\0\0\0\0\0\0\240?\0\0\0\0\0\0\0@" 1)
                       "{sts" (string.rep "[" 10000) (string.rep "}" 10000) "}")
              big (forged spheres #(set $.scene.objects (fcollect [i 1 1500000] {:kind :sphere :index i})))
              cases [[(forged spheres #(set (. $.scene.objects 1 :kind) :blob)) "objects[1].kind: unknown kind :blob"]
                     [(forged spheres #(set (. $.scene.objects 1 :radius) (/ 0 0))) "objects[1].radius: must be a positive number"]
                     [(forged spheres #(tset $.scene.objects 1000000000 {:kind :sphere})) "objects: has 1000000000 objects"]
                     [big "objects: has 1500000 objects; at most 1000000 are allowed"]
                     [(forged tree #(set (. $.scene.objects 1 :tree) (nested 45 {:kind :sphere}))) "nested deeper than 32 nodes"]
                     [(forged with-custom #(each [_ o (ipairs $.scene.objects)] (when o.tree (set o.tree.custom.lua "while true do end"))))
                      "its Lua is not the translator's (refused)"]
                     [deep "malformed data"]]]
          (each [_ [a want] (ipairs cases)]
            (let [bytes (if (= (type a) :string) a (assert (wire.encode a)))
                  msg (refused-within bytes spheres 20)]
              (assert.is_true (refused? msg) msg)
              (assert.is_truthy (msg:find want 1 true) msg)))
          ;; The real worker again.
          (assert (worker.load-source spheres file)))))

    (it "ends forged values from a worker in a message"
      (fn []
        (each [_ [vals want] (ipairs [[{:ok true :values [2]} "not a list of 2"]
                                      [{:ok true :values [(/ 0 0) [0 0 0]]} "objects[1].radius: must be a positive number from 1e-6 to 1e7, got nan"]
                                      [{:ok true :values "x"} "not a list of 2"]
                                      [{:ok 3} "not values"]
                                      [{:ok false :message "\27[2J boom"} "[2J boom"]])]
          (with-fake :forged-values (assert (wire.encode vals))
            #(let [scene (assert (worker.load-source animated file))
                   (t ok? msg) (timed #(worker.animate scene 1))]
               (assert.is_nil ok?)
               (assert.is_true (< t 10))
               (assert.is_nil (msg:find "\27" 1 true))
               (assert.is_truthy (msg:find want 1 true) msg))))))

    (it "times the check of 100,000 spheres (printed, not judged) #timing"
      (fn []
        (let [src (with-open [f (assert (io.open "test/fixtures/spheres-100000.fnl"))] (f:read :*a))
              a (real-answer src)
              times (fcollect [_ 1 5]
                      (let [c (copy a)
                            (t scene) (timed #(answer.check-scene c file src))]
                        (assert scene)
                        t))]
          (table.sort times)
          (print (string.format "answer: the check of 100,000 spheres took %.3f s (median of 5)"
                                (. times 3))))))))
