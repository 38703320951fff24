;; Offscreen OpenGL 3.3 core rendering through OSMesa and LuaJIT FFI, so tests can run generated GLSL without LÖVE or a display.
;; `pairs` under another name: a loop over `pairs` by that name is LuaJIT's ITERN,
;; which Debian 12's LuaJIT ends early once despecialised (see src/util/wire.fnl).
(local each-pair pairs)

(local ffi (require :ffi))
(local field (require :src.render.field))

;; From Mesa's include/GL/osmesa.h.
(local OSMESA_RGBA 0x1908)
(local OSMESA_FORMAT 0x22)
(local OSMESA_DEPTH_BITS 0x30)
(local OSMESA_STENCIL_BITS 0x31)
(local OSMESA_ACCUM_BITS 0x32)
(local OSMESA_PROFILE 0x33)
(local OSMESA_CORE_PROFILE 0x34)
(local OSMESA_CONTEXT_MAJOR_VERSION 0x36)
(local OSMESA_CONTEXT_MINOR_VERSION 0x37)

;; From Khronos GL/glcorearb.h.
(local GL {:UNSIGNED_BYTE 0x1401
           :FLOAT 0x1406
           :RGBA 0x1908
           :RGBA8 0x8058
           :RGBA32F 0x8814
           :TEXTURE_2D 0x0DE1
           :TEXTURE0 0x84C0
           :TEXTURE_MIN_FILTER 0x2801
           :TEXTURE_MAG_FILTER 0x2800
           :NEAREST 0x2600
           :FRAMEBUFFER 0x8D40
           :COLOR_ATTACHMENT0 0x8CE0
           :FRAMEBUFFER_COMPLETE 0x8CD5
           :FRAGMENT_SHADER 0x8B30
           :VERTEX_SHADER 0x8B31
           :COMPILE_STATUS 0x8B81
           :LINK_STATUS 0x8B82
           :INFO_LOG_LENGTH 0x8B84
           :TRIANGLES 0x0004
           :PACK_ALIGNMENT 0x0D05
           :UNPACK_ALIGNMENT 0x0CF5
           :CLAMP_READ_COLOR 0x891C
           :FALSE 0
           :MAX_FRAGMENT_UNIFORM_VECTORS 0x8DFD
           :MAX_TEXTURE_SIZE 0x0D33
           :VENDOR 0x1F00
           :RENDERER 0x1F01
           :VERSION 0x1F02
           :SHADING_LANGUAGE_VERSION 0x8B8C})

(local gl-error-names {0x0500 :GL_INVALID_ENUM
                       0x0501 :GL_INVALID_VALUE
                       0x0502 :GL_INVALID_OPERATION
                       0x0503 :GL_STACK_OVERFLOW
                       0x0504 :GL_STACK_UNDERFLOW
                       0x0505 :GL_OUT_OF_MEMORY
                       0x0506 :GL_INVALID_FRAMEBUFFER_OPERATION})

(local osmesa-cdefs
       ["void *OSMesaCreateContextAttribs(const int *attribList, void *sharelist);"
        "unsigned char OSMesaMakeCurrent(void *ctx, void *buffer, unsigned int type, int width, int height);"
        "void OSMesaDestroyContext(void *ctx);"
        "void *OSMesaGetProcAddress(const char *funcName);"])

;; GL entry points used, with their C types (GLenum/GLuint = unsigned int,
;; GLint/GLsizei = int, GLboolean = unsigned char).
(local gl-signatures
       {:glGetError "unsigned int (*)(void)"
        :glGetString "const char *(*)(unsigned int)"
        :glGetIntegerv "void (*)(unsigned int, int *)"
        :glFinish "void (*)(void)"
        :glViewport "void (*)(int, int, int, int)"
        :glPixelStorei "void (*)(unsigned int, int)"
        :glClampColor "void (*)(unsigned int, unsigned int)"
        :glReadPixels "void (*)(int, int, int, int, unsigned int, unsigned int, void *)"
        :glDrawArrays "void (*)(unsigned int, int, int)"
        :glGenVertexArrays "void (*)(int, unsigned int *)"
        :glBindVertexArray "void (*)(unsigned int)"
        :glGenTextures "void (*)(int, unsigned int *)"
        :glDeleteTextures "void (*)(int, const unsigned int *)"
        :glBindTexture "void (*)(unsigned int, unsigned int)"
        :glTexParameteri "void (*)(unsigned int, unsigned int, int)"
        :glActiveTexture "void (*)(unsigned int)"
        :glTexImage2D "void (*)(unsigned int, int, int, int, int, int, unsigned int, unsigned int, const void *)"
        :glGenFramebuffers "void (*)(int, unsigned int *)"
        :glDeleteFramebuffers "void (*)(int, const unsigned int *)"
        :glBindFramebuffer "void (*)(unsigned int, unsigned int)"
        :glFramebufferTexture2D "void (*)(unsigned int, unsigned int, unsigned int, unsigned int, int)"
        :glCheckFramebufferStatus "unsigned int (*)(unsigned int)"
        :glCreateShader "unsigned int (*)(unsigned int)"
        :glShaderSource "void (*)(unsigned int, int, const char **, const int *)"
        :glCompileShader "void (*)(unsigned int)"
        :glGetShaderiv "void (*)(unsigned int, unsigned int, int *)"
        :glGetShaderInfoLog "void (*)(unsigned int, int, int *, char *)"
        :glDeleteShader "void (*)(unsigned int)"
        :glCreateProgram "unsigned int (*)(void)"
        :glAttachShader "void (*)(unsigned int, unsigned int)"
        :glDetachShader "void (*)(unsigned int, unsigned int)"
        :glLinkProgram "void (*)(unsigned int)"
        :glGetProgramiv "void (*)(unsigned int, unsigned int, int *)"
        :glGetProgramInfoLog "void (*)(unsigned int, int, int *, char *)"
        :glDeleteProgram "void (*)(unsigned int)"
        :glUseProgram "void (*)(unsigned int)"
        :glGetUniformLocation "int (*)(unsigned int, const char *)"
        :glUniform1fv "void (*)(int, int, const float *)"
        :glUniform2fv "void (*)(int, int, const float *)"
        :glUniform3fv "void (*)(int, int, const float *)"
        :glUniform4fv "void (*)(int, int, const float *)"
        :glUniform1iv "void (*)(int, int, const int *)"})

;; Uniform type -> GL upload function, components per element, C element type.
(local uniform-kinds {:float [:glUniform1fv 1 :float]
                      :vec2 [:glUniform2fv 2 :float]
                      :vec3 [:glUniform3fv 3 :float]
                      :vec4 [:glUniform4fv 4 :float]
                      :int [:glUniform1iv 1 :int]
                      :bool [:glUniform1iv 1 :int]})

;; A full-screen triangle from gl_VertexID: (-1,-1) (3,-1) (-1,3).
(local vertex-source "#version 330 core
void main() {
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
")

(local library-names [:OSMesa :libOSMesa.so.8 :/usr/lib/x86_64-linux-gnu/libOSMesa.so.8
                      :libOSMesa.so.6])

;; The one context of this process: a table, or a failure reason string.
(var cached nil)

(fn load-osmesa []
  (each [_ decl (ipairs osmesa-cdefs)]
    (pcall ffi.cdef decl))
  (var lib nil)
  (var why nil)
  (each [_ name (ipairs library-names) &until lib]
    (let [(ok l) (pcall ffi.load name)]
      (if ok (set lib l) (set why l))))
  (if lib lib (values nil (.. "cannot load OSMesa: " (tostring why)))))

(fn gl-functions [lib]
  "A table of GL entry points cast from OSMesaGetProcAddress, or nil + reason."
  (let [gl {}]
    (var missing nil)
    (each [name sig (each-pair gl-signatures)]
      (let [ptr (lib.OSMesaGetProcAddress name)]
        (if (= ptr nil)
            (set missing name)
            (tset gl name (ffi.cast sig ptr)))))
    (if missing (values nil (.. "OSMesa has no " missing)) gl)))

(fn drain-errors [gl]
  "Clear pending GL errors; return the name of the first one, or nil."
  (var first nil)
  (var e (gl.glGetError))
  (var guard 0)
  (while (and (not= e 0) (< guard 32))
    (when (= nil first)
      (set first (or (. gl-error-names e) (string.format "GL error 0x%04X" e))))
    (set guard (+ guard 1))
    (set e (gl.glGetError)))
  first)

(fn info-log [gl object get-iv get-log]
  (let [len (ffi.new "int[1]")]
    ((. gl get-iv) object GL.INFO_LOG_LENGTH len)
    (if (<= (. len 0) 1) ""
        (let [buf (ffi.new "char[?]" (. len 0))]
          ((. gl get-log) object (. len 0) nil buf)
          (ffi.string buf)))))

(fn compile-shader [gl kind source]
  "Compile one shader; its id, or nil + the info log."
  (let [shader (gl.glCreateShader kind)
        src (ffi.new "const char *[1]" [source])
        status (ffi.new "int[1]")]
    (gl.glShaderSource shader 1 src nil)
    (gl.glCompileShader shader)
    (gl.glGetShaderiv shader GL.COMPILE_STATUS status)
    (if (not= 0 (. status 0))
        shader
        (let [log (info-log gl shader :glGetShaderiv :glGetShaderInfoLog)]
          (gl.glDeleteShader shader)
          (values nil log)))))

(fn create-context []
  (let [(lib why) (load-osmesa)]
    (if (not lib) (values nil why)
        (let [attrib-list [OSMESA_FORMAT OSMESA_RGBA
                                          OSMESA_DEPTH_BITS 0
                                          OSMESA_STENCIL_BITS 0
                                          OSMESA_ACCUM_BITS 0
                                          OSMESA_PROFILE OSMESA_CORE_PROFILE
                                          OSMESA_CONTEXT_MAJOR_VERSION 3
                                          OSMESA_CONTEXT_MINOR_VERSION 3
                                          0]
              attribs (ffi.new "int[?]" (length attrib-list) attrib-list)
              handle (lib.OSMesaCreateContextAttribs attribs nil)
              ;; OSMesa wants a colour buffer to be current; rendering goes to FBOs.
              buffer (ffi.new "uint8_t[?]" (* 16 16 4))]
          (if (= handle nil)
              (values nil "OSMesaCreateContextAttribs failed (no OpenGL 3.3 core profile?)")
              (= 0 (lib.OSMesaMakeCurrent handle buffer GL.UNSIGNED_BYTE 16 16))
              (values nil "OSMesaMakeCurrent failed")
              (let [(gl why) (gl-functions lib)]
                (if (not gl) (values nil why)
                    (let [vertex (compile-shader gl GL.VERTEX_SHADER vertex-source)
                          vao (ffi.new "unsigned int[1]")]
                      (gl.glGenVertexArrays 1 vao)
                      (gl.glBindVertexArray (. vao 0))
                      ;; Never clamp float colours on read-back (GL_FIXED_ONLY is the
                      ;; default in core profiles, but be explicit).
                      (gl.glClampColor GL.CLAMP_READ_COLOR GL.FALSE)
                      (let [err (drain-errors gl)]
                        (if (not vertex) (values nil "built-in vertex shader failed to compile")
                            err (values nil (.. "context setup failed: " err))
                            {: lib : gl : handle : buffer : vertex :vao (. vao 0)}))))))))))

(fn context []
  "The process-wide OSMesa OpenGL 3.3 core context, created on first call;
or nil + reason when OSMesa is not available."
  (when (= nil cached)
    (let [(ctx why) (create-context)]
      (set cached (or ctx (or why "unknown failure")))))
  (if (= (type cached) :table) cached (values nil cached)))

(fn numbered-lines [source line-numbers]
  "The given 1-based lines of source, each prefixed by its number, with one line of context."
  (let [lines (icollect [l (string.gmatch (.. source "\n") "([^\n]*)\n")] l)
        wanted {}
        out []]
    (each [_ n (ipairs line-numbers)]
      (for [i (- n 1) (+ n 1)] (tset wanted i true)))
    (for [i 1 (length lines)]
      (when (. wanted i)
        (table.insert out (string.format "%5d | %s" i (. lines i)))))
    (table.concat out "\n")))

(fn compile [ctx fragment-source]
  "Compile and link a complete fragment shader (\"#version 330 core\", writing
`out vec4 fragColor`) with the built-in full-screen vertex shader. Returns a
program id, or nil + the compile/link log followed by the offending source lines."
  (assert (and (= (type ctx) :table) ctx.gl) "headless.compile: expected a context")
  (assert (= (type fragment-source) :string) "headless.compile: fragment source must be a string")
  (let [gl ctx.gl]
    (drain-errors gl)
    (let [(fragment log) (compile-shader gl GL.FRAGMENT_SHADER fragment-source)]
      (if (not fragment)
          (let [line-numbers (icollect [n (string.gmatch log "%d+:(%d+)%(%d+%)")] (tonumber n))
                listing (numbered-lines fragment-source line-numbers)]
            (values nil (.. "fragment shader failed to compile:\n" log
                            (if (= listing "") "" (.. "\n" listing)))))
          (let [program (gl.glCreateProgram)
                status (ffi.new "int[1]")]
            (gl.glAttachShader program ctx.vertex)
            (gl.glAttachShader program fragment)
            (gl.glLinkProgram program)
            (gl.glGetProgramiv program GL.LINK_STATUS status)
            (gl.glDetachShader program ctx.vertex)
            (gl.glDetachShader program fragment)
            (gl.glDeleteShader fragment)
            (if (not= 0 (. status 0))
                program
                (let [log (info-log gl program :glGetProgramiv :glGetProgramInfoLog)]
                  (gl.glDeleteProgram program)
                  (values nil (.. "program failed to link:\n" log)))))))))

(fn prepare-texture [u unit]
  ;; A float texture uniform (a field's): its texels as a C float array, drawn from
  ;; texture unit `unit`.
  (let [{: width : height : data} u.texture
        floats (when (= nil data) (field.floats-of u.texture))
        n (* width height 4)]
    (if floats
        ;; Already float32 of the texture's size (field.textures).
        {:name u.name :texture? true : unit : width : height :arr floats}
        (let [arr (ffi.new "float[?]" n)]
          (assert (<= (length data) n)
                  (.. "headless.render: texture " u.name " has more values than its size holds"))
          (for [j 1 (length data)] (tset arr (- j 1) (. data j)))
          {:name u.name :texture? true : unit : width : height : arr}))))

(fn prepare-uniforms [uniforms]
  "Check uniform specs and pack their values into C arrays before any GL work."
  (var units 0)
  (icollect [i u (ipairs (or uniforms []))]
    (if (= u.type :texture)
        (do (set units (+ units 1)) (prepare-texture u units))
        ;; An image this module rendered (a picture of centre rays, uniforms.prior):
        ;; uploaded as it is, row 0 first, so that a shader reading it at its y-down
        ;; pixel coordinates finds each pixel where it was drawn.
        (= u.type :image)
        (let [{: width : height : pixels : float?} u.image]
          (set units (+ units 1))
          {:name u.name :texture? true :unit units : width : height :arr pixels
           :format (if float? GL.RGBA32F GL.RGBA8) :kind (if float? GL.FLOAT GL.UNSIGNED_BYTE)})
    (let [kind (. uniform-kinds u.type)
          vals (or u.values [])]
      (assert (= (type u.name) :string) (.. "headless.render: uniform " i " has no :name"))
      (assert kind (.. "headless.render: uniform " u.name " has unknown type " (tostring u.type)))
      (let [[fn-name per c-type] kind
            n (length vals)
            arr (ffi.new (.. c-type "[?]") (math.max n 1))]
        (assert (and (> n 0) (= 0 (% n per)))
                (string.format "headless.render: uniform %s (%s) needs a multiple of %d values, got %d"
                               u.name u.type per n))
        (for [j 1 n]
          (let [v (. vals j)]
            (tset arr (- j 1) (if (= v true) 1 (= v false) 0 v))))
        {:name u.name : fn-name :count (/ n per) : arr})))))

(fn set-uniforms [gl program prepared]
  "Upload prepared uniforms to the current program, skipping optimised-away ones.
Returns the textures it made, to delete after the draw."
  (let [made []]
    (each [_ u (ipairs prepared)]
      (let [loc (gl.glGetUniformLocation program u.name)]
        (if (and u.texture? (not= loc -1))
            (let [tex (ffi.new "unsigned int[1]")]
              (gl.glActiveTexture (+ GL.TEXTURE0 u.unit))
              (gl.glGenTextures 1 tex)
              (gl.glBindTexture GL.TEXTURE_2D (. tex 0))
              (gl.glTexParameteri GL.TEXTURE_2D GL.TEXTURE_MIN_FILTER GL.NEAREST)
              (gl.glTexParameteri GL.TEXTURE_2D GL.TEXTURE_MAG_FILTER GL.NEAREST)
              (gl.glPixelStorei GL.UNPACK_ALIGNMENT 1)
              (gl.glTexImage2D GL.TEXTURE_2D 0 (or u.format GL.RGBA32F) u.width u.height 0 GL.RGBA
                               (or u.kind GL.FLOAT) u.arr)
              (gl.glUniform1iv loc 1 (ffi.new "int[1]" u.unit))
              (gl.glActiveTexture GL.TEXTURE0)
              (table.insert made tex))
            (and (not u.texture?) (not= loc -1))
            ((. gl u.fn-name) loc u.count u.arr))))
    made))

(fn render [ctx program options]
  "Draw program over a width x height target and read it back. options:
{:width :height :float? (RGBA32F target instead of RGBA8) :uniforms [{:name
:type :values} ...]} with type one of float int bool vec2 vec3 vec4 and values a
flat sequence of numbers. Returns {:width :height :float? :pixels}, pixels an FFI
uint8_t or float array of width*height*4 RGBA with row 0 = top row; or nil +
message on a GL error."
  (assert (and (= (type ctx) :table) ctx.gl) "headless.render: expected a context")
  (assert (= (type program) :number) "headless.render: expected a program id")
  (let [{: width : height} options
        float? (not (not options.float?))
        uniforms (prepare-uniforms options.uniforms)
        gl ctx.gl]
    (assert (and (= (type width) :number) (>= width 1) (= width (math.floor width)))
            "headless.render: width must be a positive integer")
    (assert (and (= (type height) :number) (>= height 1) (= height (math.floor height)))
            "headless.render: height must be a positive integer")
    (drain-errors gl)
    (let [fbo (ffi.new "unsigned int[1]")
          tex (ffi.new "unsigned int[1]")
          n (* width height 4)
          c-type (if float? :float :uint8_t)
          row-bytes (* width 4 (if float? 4 1))
          raw (ffi.new (.. c-type "[?]") n)
          pixels (ffi.new (.. c-type "[?]") n)
          textures []]
      (gl.glGenTextures 1 tex)
      (gl.glBindTexture GL.TEXTURE_2D (. tex 0))
      (gl.glTexParameteri GL.TEXTURE_2D GL.TEXTURE_MIN_FILTER GL.NEAREST)
      (gl.glTexParameteri GL.TEXTURE_2D GL.TEXTURE_MAG_FILTER GL.NEAREST)
      (gl.glTexImage2D GL.TEXTURE_2D 0 (if float? GL.RGBA32F GL.RGBA8) width height 0
                       GL.RGBA (if float? GL.FLOAT GL.UNSIGNED_BYTE) nil)
      (gl.glGenFramebuffers 1 fbo)
      (gl.glBindFramebuffer GL.FRAMEBUFFER (. fbo 0))
      (gl.glFramebufferTexture2D GL.FRAMEBUFFER GL.COLOR_ATTACHMENT0 GL.TEXTURE_2D (. tex 0) 0)
      (let [status (gl.glCheckFramebufferStatus GL.FRAMEBUFFER)
            complete? (= status GL.FRAMEBUFFER_COMPLETE)]
        (when complete?
          (gl.glViewport 0 0 width height)
          (gl.glUseProgram program)
          (each [_ t (ipairs (set-uniforms gl program uniforms))]
            (table.insert textures t))
          (gl.glDrawArrays GL.TRIANGLES 0 3)
          (gl.glFinish)
          (gl.glPixelStorei GL.PACK_ALIGNMENT 1)
          (gl.glReadPixels 0 0 width height GL.RGBA (if float? GL.FLOAT GL.UNSIGNED_BYTE) raw))
        (let [err (drain-errors gl)]
          (gl.glUseProgram 0)
          (gl.glBindFramebuffer GL.FRAMEBUFFER 0)
          (gl.glDeleteFramebuffers 1 fbo)
          (gl.glBindTexture GL.TEXTURE_2D 0)
          (gl.glDeleteTextures 1 tex)
          (each [_ t (ipairs textures)] (gl.glDeleteTextures 1 t))
          (drain-errors gl)
          (if (not complete?)
              (values nil (string.format "framebuffer incomplete (status 0x%04X) for %dx%d %s target%s"
                                         status width height (if float? :RGBA32F :RGBA8)
                                         (if err (.. ", " err) "")))
              err
              (values nil (.. "GL error while rendering: " err))
              (do
                ;; glReadPixels gives the bottom row first; flip so row 0 is the top.
                (for [y 0 (- height 1)]
                  (ffi.copy (+ pixels (* y width 4)) (+ raw (* (- height 1 y) width 4)) row-bytes))
                {: width : height : float? : pixels})))))))

(fn pixel [image x y]
  "The r g b a values of image at column x, row y (0-based from the top-left):
0-255 for 8-bit images, raw floats for float images."
  (assert (and (>= x 0) (< x image.width) (>= y 0) (< y image.height))
          (string.format "headless.pixel: (%s, %s) outside %dx%d image"
                         (tostring x) (tostring y) image.width image.height))
  (let [i (* 4 (+ x (* y image.width)))
        p image.pixels]
    (values (tonumber (. p i)) (tonumber (. p (+ i 1)))
            (tonumber (. p (+ i 2))) (tonumber (. p (+ i 3))))))

(fn release [ctx program]
  "Delete a program made by compile."
  (assert (and (= (type ctx) :table) ctx.gl) "headless.release: expected a context")
  (ctx.gl.glDeleteProgram program)
  (drain-errors ctx.gl)
  nil)

(fn limits [ctx]
  "{:max-fragment-uniform-vectors :max-texture-size :renderer :version :glsl-version :vendor} of the context."
  (assert (and (= (type ctx) :table) ctx.gl) "headless.limits: expected a context")
  (let [gl ctx.gl
        v (ffi.new "int[1]")
        get-int (fn [pname] (gl.glGetIntegerv pname v) (. v 0))
        get-string (fn [pname]
                     (let [s (gl.glGetString pname)]
                       (if (= s nil) "" (ffi.string s))))]
    {:max-fragment-uniform-vectors (get-int GL.MAX_FRAGMENT_UNIFORM_VECTORS)
     :max-texture-size (get-int GL.MAX_TEXTURE_SIZE)
     :renderer (get-string GL.RENDERER)
     :version (get-string GL.VERSION)
     :glsl-version (get-string GL.SHADING_LANGUAGE_VERSION)
     :vendor (get-string GL.VENDOR)}))

{: context : compile : render : pixel : release : limits}
