;; expect: test/corpus/nan-environment.fnl:2: environment[1]: must be a colour of three numbers from 0 to 1, got nan
{:environment [(/ 0 0) 1 1]
 :objects []}
