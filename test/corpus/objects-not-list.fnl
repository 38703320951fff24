;; expect: test/corpus/objects-not-list.fnl:2: objects: must be a list [...] of objects, not a table with named fields
{:objects {:ball {:kind :sphere :radius 1}}}
