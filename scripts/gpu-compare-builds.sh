#!/usr/bin/env bash
# Frame times of several builds of pss side by side on one GPU (issue 29): for a change that
# only a device can judge (work order, register limits), build each variant here, carry the
# binaries, and run them in one call, alternating, so that they meet the same card in the
# same state. Each renders the paper's cases with --frames 10 (the median frame, device
# time), three runs each; the table gives the median of the runs in milliseconds.
#   scripts/gpu-compare-builds.sh NAME=PATH/TO/pss [NAME=PATH ...]
# PSS_COMPARE_RUNS (default 3), PSS_COMPARE_FRAMES (default 10) and PSS_COMPARE_BACKEND
# (default cuda; cpu tries the script where there is no device).
set -euo pipefail
(($# > 0)) || { echo "usage: $0 NAME=PATH/TO/pss [NAME=PATH ...]" >&2; exit 2; }
builds=()
for build in "$@"; do  # the paths as given, from the caller's folder
  [[ -x ${build#*=} && $build == *=* ]] || { echo "$0: not NAME=an executable: $build" >&2; exit 2; }
  builds+=("${build%%=*}=$(realpath "${build#*=}")")
done
set -- "${builds[@]}"
cd "$(dirname "$0")/.."
runs=${PSS_COMPARE_RUNS:-3}
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
cases=(
  "bunny 512², 2 iterations, reflection|render data/bun_zipper.ply --size 512x512 --reflections --iterations 2"
  "bunny 1920×1080, shadows, reflection|render data/bun_zipper.ply --size 1920x1080 --shadows --reflections"
  "engine 512², predictor-corrector|volume data/engine_256x256x128_uint8.nrrd --iso 90 --size 512x512"
  "engine 512², predictor|volume data/engine_256x256x128_uint8.nrrd --iso 90 --size 512x512 --method predictor"
)
printf '| case |'
for build in "$@"; do printf ' %s ms |' "${build%%=*}"; done
printf '\n|---|'
for _ in "$@"; do printf -- '---|'; done
printf '\n'
for c in "${cases[@]}"; do
  name=${c%%|*}
  args=${c#*|}
  declare -A times=()
  for ((r = 0; r < runs; ++r)); do
    for build in "$@"; do
      # shellcheck disable=SC2086  # args is a list of words
      "${build#*=}" $args -o "$scratch/out.png" --backend ${PSS_COMPARE_BACKEND:-cuda} --frames ${PSS_COMPARE_FRAMES:-10} --stats "$scratch/stats.json" >/dev/null
      times[${build%%=*}]+="$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["frame_seconds"])' \
        "$scratch/stats.json") "
    done
  done
  printf '| %s |' "$name"
  for build in "$@"; do
    python3 -c 'import statistics,sys; print(" %.3f |" % (1e3 * statistics.median(map(float, sys.argv[1:]))), end="")' \
      ${times[${build%%=*}]}
  done
  printf '\n'
  unset times
done
