;; expect: test/corpus/objects-missing.fnl:2: objects: missing; a scene needs :objects [...] (it may be empty)
{:name "no objects"
 :camera {:fov 60}}
