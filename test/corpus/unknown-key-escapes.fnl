;; expect: test/corpus/unknown-key-escapes.fnl:2: ["\027[2J\027[31mFAKE: all tests passed\n"]: unknown field; known fields: :camera :environment :light :lighting :name :objects :render
{"\27[2J\27[31mFAKE: all tests passed\n" 1
 :objects []}
