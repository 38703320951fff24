;; `make golden`: (re)creates the golden images that are missing or fail their budget,
;; and says which changed. The test run itself never writes a golden.
(local golden (require :src.verify.golden))
(let [failures (golden.update!)]
  (when (> failures 0) (os.exit 1)))
