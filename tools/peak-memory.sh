#!/usr/bin/env bash
# Runs a command and prints the peak of the resident memory of it and all its
# descendants together (the scene worker, the compile helpers, the mesher's forked
# shares), sampled every 20 ms from /proc. Each process counts its proportional
# share of the pages it shares with others (Pss, from smaps_rollup: a forked child
# shares its parent's pages until either writes them, and a sum of resident sizes
# would count those twice); VmRSS where the kernel has no smaps_rollup:
#   bash tools/peak-memory.sh love . --render scenes/seed.fnl --out /tmp/seed.png
# The last line is 'peak N MB (A MB in PROCESS, ...)'; the exit code is the command's.
# Used by test/million_spec.fnl (issue 43: a million spheres within 1.5 GB in all).
set -u
"$@" &
root=$!
peak=0
detail=""
descendants() {
  # Every process whose ancestry leads to $1, from the parent ids in /proc/*/stat
  # (pid (name) state ppid ...: the name may hold spaces and parentheses).
  local want=" $1 " found=1 pid ppid line
  while [ $found -eq 1 ]; do
    found=0
    for stat in /proc/[0-9]*/stat; do
      { read -r line < "$stat"; } 2>/dev/null || continue
      pid=${line%% *}
      read -r _ ppid _ <<< "${line##*) }"
      case "$want" in *" $pid "*) continue ;; esac
      case "$want" in *" $ppid "*) want="$want$pid "; found=1 ;; esac
    done
  done
  echo "$want"
}
while kill -0 "$root" 2>/dev/null; do
  sum=0
  parts=""
  for pid in $(descendants "$root"); do
    if [ -r "/proc/$pid/smaps_rollup" ]; then
      kb=$(awk '/^Pss:/ {print $2}' "/proc/$pid/smaps_rollup" 2>/dev/null)
    else
      kb=$(awk '/^VmRSS:/ {print $2}' "/proc/$pid/status" 2>/dev/null)
    fi
    [ -n "$kb" ] || continue
    sum=$((sum + kb))
    name=$(tr '\0' ' ' < "/proc/$pid/cmdline" 2>/dev/null | cut -c1-60)
    parts="$parts, $((kb / 1024)) MB in ${name% }"
  done
  if [ "$sum" -gt "$peak" ]; then peak=$sum; detail=${parts#, }; fi
  sleep 0.02
done
wait "$root"
rc=$?
echo "peak $((peak / 1024)) MB ($detail)"
exit $rc
