;; expect: test/corpus/forbidden-thread-lua-double.fnl:3: (lua ...) is not allowed: scene files are data and run no compile-time code
;; -> into ->> into lua: the form only exists after both macros expand.
{:objects [{:kind :sphere :radius (-> "os.execute('touch test/out/corpus-trace/thread-lua-double') or 1" (->> lua))}]}
