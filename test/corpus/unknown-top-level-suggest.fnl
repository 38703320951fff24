;; expect: test/corpus/unknown-top-level-suggest.fnl:3: objcts: unknown field (did you mean :objects?); known fields: :camera :environment :light :lighting :name :objects :render
{:name "typo"
 :objcts []}
