;; expect: test/corpus/objects-string.fnl:2: objects: must be a list of objects, got "spheres"
{:objects "spheres"}
