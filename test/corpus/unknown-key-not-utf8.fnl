;; expect: test/corpus/unknown-key-not-utf8.fnl:2: ["caf\233"]: unknown field; known fields: :camera :environment :light :lighting :name :objects :render
{"caf\233" 1
 :objects []}
