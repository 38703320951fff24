;; expect: test/corpus/unknown-top-level-no-suggestion.fnl:3: soundtrack: unknown field; known fields: :camera :environment :light :lighting :name :objects :render
{:name "music"
 :soundtrack "song.ogg"
 :objects []}
