#!/usr/bin/env bash
# The CUDA compiler launcher of the library (src/CMakeLists.txt): runs the compile with ptxas's
# report of every kernel's stack frame and spills (-Xptxas=-v) and keeps that report beside
# the object, OBJECT.ptxas, for the stack budget test (tests/gpu/kernel_stacks.py). The
# report is left out of the build's output; everything else nvcc says is passed on.
set -uo pipefail
out=
for ((i = 1; i < $#; ++i)); do
  if [[ ${!i} == -o ]]; then
    next=$((i + 1))
    out=${!next}
  fi
done
[[ -n $out ]] || exec "$@"
"$@" -Xptxas=-v 2> "$out.ptxas"
status=$?
grep -v -e '^ptxas info' -e '^    [0-9]* bytes stack frame' "$out.ptxas" >&2
exit $status
