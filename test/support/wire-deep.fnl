;; One fresh process's wire round trip of a deep tree (test/iteration_spec.fnl):
;;   luajit tools/fnl.lua test/support/wire-deep.fnl
;; prints `intact`, or `empty at DEPTH` where a node came back with neither its kind
;; nor its children. Debian 12's LuaJIT ended the encoder's loop over a node's keys
;; early in about 1 of 6 fresh processes (LuaJIT issue 827), on the first round trip.
(local wire (require :src.util.wire))

(fn nested [depth leaf]
  (var node leaf)
  (for [_ 1 depth] (set node {:kind :union :children [node]}))
  node)

(fn empty-at [node depth]
  (if (not= (type node) :table) nil
      (and (= node.children nil) (= node.kind nil)) depth
      node.children (empty-at (. node.children 1) (+ depth 1))))

(let [answer {:scene {:objects [{:kind :union :index 1 :tree (nested 45 {:kind :sphere})}]}}
      copy (wire.decode (assert (wire.encode answer)))]
  (case (empty-at (. copy.scene.objects 1 :tree) 1)
    depth (print (.. "empty at " depth))
    _ (print "intact")))
