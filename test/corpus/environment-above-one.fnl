;; expect: test/corpus/environment-above-one.fnl:2: environment[3]: must be a colour of three numbers from 0 to 1, got 2
{:environment [0.5 0.5 2]
 :objects []}
