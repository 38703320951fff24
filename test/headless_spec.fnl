;; Specs for src/backend/headless.fnl: OSMesa offscreen rendering of fragment shaders, uniforms, float targets and errors.
(local headless (require :src.backend.headless))

(local gradient-source "#version 330 core
out vec4 fragColor;
uniform vec2 uSize;
void main() {
    fragColor = vec4(gl_FragCoord.x / uSize.x, gl_FragCoord.y / uSize.y, 0.25, 1.0);
}
")

(fn unorm8 [v]
  "What an RGBA8 target stores for v in [0, 1]."
  (math.floor (+ 0.5 (* 255 v))))

(fn near? [expected actual tolerance]
  (<= (math.abs (- expected actual)) tolerance))

(fn with-program [ctx source f]
  "Compile source, call (f program), release it even when f fails."
  (let [(program err) (headless.compile ctx source)]
    (assert.is_truthy program err)
    (let [(ok result) (pcall f program)]
      (headless.release ctx program)
      (when (not ok) (error result 0))
      result)))

(fn check-gradient [ctx program w h float?]
  (let [(image err) (headless.render ctx program {:width w :height h :float? float?
                                                  :uniforms [{:name :uSize :type :vec2 :values [w h]}]})]
    (assert.is_truthy image err)
    (assert.are.equal w image.width)
    (assert.are.equal h image.height)
    (assert.are.equal float? image.float?)
    ;; Row 0 of the image is the top row: the largest gl_FragCoord.y.
    (each [_ [x y] (ipairs [[0 0] [(- w 1) 0] [0 (- h 1)] [(- w 1) (- h 1)]
                            [(math.floor (/ w 2)) (math.floor (/ h 3))]])]
      (let [(r g b a) (headless.pixel image x y)
            er (/ (+ x 0.5) w)
            eg (/ (- h y 0.5) h)]
        (if float?
            (do
              (assert.is_true (near? er r 1e-6) (string.format "r at %d,%d: %s" x y r))
              (assert.is_true (near? eg g 1e-6) (string.format "g at %d,%d: %s" x y g))
              (assert.are.equal 0.25 b)
              (assert.are.equal 1 a))
            (do
              (assert.is_true (near? (unorm8 er) r 1) (string.format "r at %d,%d: %s" x y r))
              (assert.is_true (near? (unorm8 eg) g 1) (string.format "g at %d,%d: %s" x y g))
              (assert.is_true (near? 64 b 1))
              (assert.are.equal 255 a)))))
    image))

(describe "headless"
  (fn []
    (let [(ctx why) (headless.context)]
      (if (not ctx)
          (pending (.. "OSMesa is not available: " (tostring why)))
          (do
            (it "caches one context and reports its limits"
              (fn []
                (assert.are.equal ctx (headless.context))
                (let [limits (headless.limits ctx)]
                  (assert.is_true (>= limits.max-fragment-uniform-vectors 4000))
                  (assert.is_string limits.renderer)
                  (assert.is_true (> (length limits.renderer) 0))
                  (assert.matches "Core Profile" limits.version))))

            (it "renders a gradient with pixel (0,0) at the top-left"
              (fn []
                (with-program ctx gradient-source
                  (fn [program]
                    (let [image (check-gradient ctx program 64 32 false)
                          (_ g-top) (headless.pixel image 10 0)
                          (_ g-bottom) (headless.pixel image 10 31)
                          (r-left) (headless.pixel image 0 10)
                          (r-right) (headless.pixel image 63 10)]
                      (assert.is_true (> g-top 240))
                      (assert.is_true (< g-bottom 15))
                      (assert.is_true (< r-left 15))
                      (assert.is_true (> r-right 240)))))))

            (it "renders several sizes and both targets in sequence"
              (fn []
                (with-program ctx gradient-source
                  (fn [program]
                    (each [_ [w h float?] (ipairs [[1 1 false] [3 7 true] [640 480 false]
                                                   [257 13 true] [13 257 false] [2 2 true]
                                                   [64 32 false]])]
                      (check-gradient ctx program w h float?))))))

            (it "delivers uniforms of every type"
              (fn []
                (with-program ctx "#version 330 core
out vec4 fragColor;
uniform float uF;
uniform int uI;
uniform bool uB;
uniform bool uB2;
uniform vec2 uV2;
uniform vec3 uV3;
uniform vec4 uV4;
uniform vec4 uArr[3];
uniform float uFa[2];
uniform int uIa[2];
void main() {
    int x = int(gl_FragCoord.x);
    vec4 c = vec4(0.0);
    if (x == 0) c = vec4(uF, 0.0, 0.0, 0.0);
    else if (x == 1) c = vec4(float(uI), 0.0, 0.0, 0.0);
    else if (x == 2) c = vec4(uB ? 1.0 : 0.0, uB2 ? 1.0 : 0.0, 0.0, 0.0);
    else if (x == 3) c = vec4(uV2, 0.0, 0.0);
    else if (x == 4) c = vec4(uV3, 0.0);
    else if (x == 5) c = uV4;
    else if (x <= 8) c = uArr[x - 6];
    else if (x == 9) c = vec4(uFa[0], uFa[1], float(uIa[0]), float(uIa[1]));
    fragColor = c;
}
"
                  (fn [program]
                    (let [(image err)
                          (headless.render ctx program
                                           {:width 10 :height 1 :float? true
                                            :uniforms [{:name :uF :type :float :values [0.25]}
                                                       {:name :uI :type :int :values [-7]}
                                                       {:name :uB :type :bool :values [true]}
                                                       {:name :uB2 :type :bool :values [0]}
                                                       {:name :uV2 :type :vec2 :values [1.5 -2]}
                                                       {:name :uV3 :type :vec3 :values [3 4 5]}
                                                       {:name :uV4 :type :vec4 :values [6 7 8 1234.5]}
                                                       {:name :uArr :type :vec4
                                                        :values [1 2 3 4 5 6 7 8 9 10 11 12]}
                                                       {:name "uFa[0]" :type :float :values [0.5 -0.5]}
                                                       {:name :uIa :type :int :values [3 -4]}
                                                       {:name :uMissing :type :vec4 :values [1 2 3 4]}]})
                          expect [[0.25 0 0 0] [-7 0 0 0] [1 0 0 0] [1.5 -2 0 0] [3 4 5 0]
                                  [6 7 8 1234.5] [1 2 3 4] [5 6 7 8] [9 10 11 12] [0.5 -0.5 3 -4]]]
                      (assert.is_truthy image err)
                      (each [i e (ipairs expect)]
                        (assert.are.same e [(headless.pixel image (- i 1) 0)])))))))

            (it "keeps values above 1, Inf and NaN exactly in a float target"
              (fn []
                (with-program ctx "#version 330 core
out vec4 fragColor;
uniform float uZero;
uniform float uBig;
void main() {
    fragColor = gl_FragCoord.y < 1.0
        ? vec4(1.0 / uZero, -1.0 / uZero, uZero / uZero, uBig)
        : vec4(uBig, 2.0, 0.5, -3.0);
}
"
                  (fn [program]
                    (let [uniforms [{:name :uZero :type :float :values [0]}
                                    {:name :uBig :type :float :values [3.75]}]
                          (image err) (headless.render ctx program {:width 3 :height 2 :float? true
                                                                    : uniforms})]
                      (assert.is_truthy image err)
                      ;; gl_FragCoord.y < 1 is the bottom row, which is image row 1.
                      (let [(r g b a) (headless.pixel image 2 1)]
                        (assert.are.equal math.huge r)
                        (assert.are.equal (- math.huge) g)
                        (assert.is_true (not= b b) "NaN expected")
                        (assert.are.equal 3.75 a))
                      (assert.are.same [3.75 2 0.5 -3] [(headless.pixel image 0 0)])
                      ;; The same shader into an 8-bit target clamps.
                      (let [image8 (headless.render ctx program {:width 3 :height 2 : uniforms})]
                        (assert.are.same [255 255 128 0] [(headless.pixel image8 1 0)])))))))

            (it "returns the compile log with numbered source lines on a compile error"
              (fn []
                (let [(program err) (headless.compile ctx "#version 330 core
out vec4 fragColor;
void main() {
    fragColor = vec3(1.0);
}
")]
                  (assert.is_nil program)
                  (assert.matches "error" err)
                  (assert.matches "0:4" err)
                  (assert.matches "4 |     fragColor = vec3%(1.0%);" err))))

            (it "returns the link log on a link error"
              (fn []
                (let [(program err) (headless.compile ctx "#version 330 core
out vec4 fragColor;
vec4 shade();
void main() { fragColor = shade(); }
")]
                  (assert.is_nil program)
                  (assert.matches "link" err))))

            (it "compiles, links and fills a uniform array of 4000 vec4"
              (fn []
                (with-program ctx "#version 330 core
out vec4 fragColor;
uniform vec4 uBig[4000];
void main() {
    fragColor = uBig[int(gl_FragCoord.x)];
}
"
                  (fn [program]
                    (let [n 4000
                          big-values (fcollect [i 0 (- (* 4 n) 1)] (* i 0.25))
                          (image err) (headless.render ctx program
                                                       {:width n :height 1 :float? true
                                                        :uniforms [{:name :uBig :type :vec4 :values big-values}]})]
                      (assert.is_truthy image err)
                      (each [_ x (ipairs [0 1 1234 3999])]
                        (let [i (* 4 x)]
                          (assert.are.same [(* i 0.25) (* (+ i 1) 0.25) (* (+ i 2) 0.25) (* (+ i 3) 0.25)]
                                           [(headless.pixel image x 0)]))))))))

            (it "reports GL errors from render as nil + message"
              (fn []
                (with-program ctx gradient-source
                  (fn [program]
                    ;; uSize is a vec2: uploading it as a float is GL_INVALID_OPERATION.
                    (let [(image err) (headless.render ctx program {:width 4 :height 4
                                                                    :uniforms [{:name :uSize :type :float :values [1]}]})]
                      (assert.is_nil image)
                      (assert.matches "GL_INVALID_OPERATION" err))
                    ;; The context is still usable afterwards.
                    (check-gradient ctx program 5 5 false)))))

            (it "treats malformed uniform specs as programmer errors"
              (fn []
                (with-program ctx gradient-source
                  (fn [program]
                    (assert.has_error
                      (fn [] (headless.render ctx program {:width 2 :height 2
                                                           :uniforms [{:name :uSize :type :mat4 :values [1]}]})))
                    (assert.has_error
                      (fn [] (headless.render ctx program {:width 2 :height 2
                                                           :uniforms [{:name :uSize :type :vec2 :values [1 2 3]}]})))
                    ;; Nothing was left bound: the next render works.
                    (check-gradient ctx program 3 3 true)))))

            (it "cannot render a released program"
              (fn []
                (let [program (headless.compile ctx gradient-source)]
                  (headless.release ctx program)
                  (let [(image err) (headless.render ctx program {:width 2 :height 2})]
                    (assert.is_nil image)
                    (assert.is_string err))))))))))
