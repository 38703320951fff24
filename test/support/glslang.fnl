;; glslangValidator on a fragment shader's text, shared by the shader specs.

(fn ok? [source]
  "True and the validator's output when `source` (a fragment shader) validates, else
false and the output."
  (let [base (os.tmpname)
        path (.. base ".frag")]
    ;; os.tmpname made `base`: only its unique name is needed.
    (os.remove base)
    (with-open [f (assert (io.open path :wb))] (f:write source))
    (let [out (with-open [p (io.popen (.. "glslangValidator " path " 2>&1; echo \"exit:$?\""))]
                (p:read :*a))]
      (os.remove path)
      (values (not= nil (out:match "exit:0%s*$")) out))))

(fn preprocessed [source]
  "`source` as the GLSL preprocessor leaves it (glslangValidator -E): macros
expanded, directives gone."
  (let [base (os.tmpname)
        path (.. base ".frag")]
    (os.remove base)
    (with-open [f (assert (io.open path :wb))] (f:write source))
    (let [out (with-open [p (io.popen (.. "glslangValidator -E " path " 2>&1"))]
                (p:read :*a))]
      (os.remove path)
      out)))

{: ok? : preprocessed}
