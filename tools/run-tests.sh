#!/usr/bin/env bash
# Runs the whole busted suite and ends with one line 'N passed, N failed, N skipped'
# (busted's own summary counts errors apart from failures; both count as failed here).
# With --check (`make check`): the fast loop, the specs that need no LÖVE window and no
# GPU (codegen_spec's glslangValidator is a plain program), the whole corpus through the
# loader but one file per class through the app, and 2000 fuzz cases. A new pure spec
# belongs in the list below.
set -uo pipefail
cd "$(dirname "$0")/.."
if [ "${1:-}" = "--check" ]; then
  shift
  export CORPUS_SAMPLE=1 FUZZ_CASES="${FUZZ_CASES:-2000}"
  set -- "$@" test/adaptive_spec.fnl test/animation_spec.fnl test/article_spec.fnl \
    test/bounds_spec.fnl test/camera_spec.fnl test/codegen_spec.fnl test/corpus_spec.fnl \
    test/data_spec.fnl \
    test/field_spec.fnl test/fuzz_spec.fnl test/operations_spec.fnl test/params_spec.fnl \
    test/plan_spec.fnl test/png_spec.fnl test/primitives_spec.fnl \
    test/probe_input_spec.fnl test/progress_spec.fnl test/reference_spec.fnl \
    test/repeat_cells_spec.fnl test/sandbox_spec.fnl test/scene_spec.fnl test/states_spec.fnl \
    test/tape_spec.fnl test/translate_spec.fnl test/uniforms_spec.fnl test/watch_spec.fnl \
    test/worker_spec.fnl test/wire_spec.fnl test/mesh_spec.fnl
fi
log=$(mktemp)
trap 'rm -f "$log"' EXIT
busted "$@" 2>&1 | tee "$log"
rc=${PIPESTATUS[0]}
summary=$(grep -E '^[0-9]+ successes? / [0-9]+ failures? / [0-9]+ errors? / [0-9]+ pending' "$log" | tail -n 1)
if [ -z "$summary" ]; then
  echo "busted printed no summary (exit $rc)"
  echo "0 passed, 1 failed"
  exit 1
fi
read -r passed failures errors pending < <(echo "$summary" | awk '{print $1, $4, $7, $10}')
echo "$passed passed, $((failures + errors)) failed, $pending skipped"
exit "$rc"
