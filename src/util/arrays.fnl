;; Arrays made at their size, for the mesher's long lists of numbers (one number a
;; point, a cell, a crossing): LuaJIT's table.new (a table whose array part is
;; allocated once, not grown by doubling) and FFI arrays of fixed types, zeroed, read
;; and written with the same `.` and `tset` as a table. Without LuaJIT's extensions
;; (plain Lua) each is a plain table, of zeros where the FFI's would be.

(local ffi (let [(ok? m) (pcall require :ffi)] (when ok? m)))

(local table-new
  (let [(ok? new) (pcall require :table.new)]
    (if ok? (fn [n] (new n 0)) (fn [] []))))

(fn zeros [n] (fcollect [_ 1 n] 0))

(fn int-array [n]
  "An array of 32-bit integers 1 to n, all 0."
  (if ffi (ffi.new "int32_t[?]" (+ n 1)) (zeros n)))

(fn byte-array [n]
  "An array of bytes 1 to n, all 0."
  (if ffi (ffi.new "uint8_t[?]" (+ n 1)) (zeros n)))

(fn float-array [n]
  "An array of doubles 1 to n, all 0."
  (if ffi (ffi.new "double[?]" (+ n 1)) (zeros n)))

{: table-new : int-array : byte-array : float-array}
