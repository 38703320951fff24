;; glslangValidator on a fragment shader's text, shared by the shader specs.
(local {: sh} (require :test.support.app))

(fn on-file [source options]
  "glslangValidator with `options` on `source` written to a file of its own: its exit
code and output."
  (let [base (os.tmpname)
        path (.. base ".frag")]
    ;; os.tmpname made `base`: only its unique name is needed.
    (os.remove base)
    (with-open [f (assert (io.open path :wb))] (f:write source))
    (let [(code out) (sh (.. "glslangValidator " options path))]
      (os.remove path)
      (values code out))))

(fn validate [source]
  "The validator's exit code and output for `source` (a fragment shader)."
  (on-file source ""))

(fn ok? [source]
  "True and the validator's output when `source` (a fragment shader) validates, else
false and the output."
  (let [(code out) (validate source)]
    (values (= 0 code) out)))

(fn preprocessed [source]
  "`source` as the GLSL preprocessor leaves it (glslangValidator -E): macros
expanded, directives gone."
  (let [(_ out) (on-file source "-E ")] out))

{: validate : ok? : preprocessed}
