;; expect: test/corpus/type-environment-number.fnl:2: environment: must be a colour of three numbers from 0 to 1, got 0.5
{:environment 0.5
 :objects []}
