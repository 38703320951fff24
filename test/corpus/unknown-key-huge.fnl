;; expect: test/corpus/unknown-key-huge.fnl:2: ["kkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkk"... (4000000 bytes)]: unknown field; known fields: :camera :environment :light :lighting :name :objects :render
(let [k (string.rep "k" 1000000)]
  {(.. k k k k) 1 :objects []})
