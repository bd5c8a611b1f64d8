#!/usr/bin/env bash
# Fuzzes pss's file readers and its command line with libFuzzer (docs/fuzzing.md).
#   scripts/fuzz.sh [TARGET|all] [SECONDS]     TARGET: ply xyz obj stl pcd las raw nrrd metaimage nifti cli
# Builds the targets with clang, ASan and UBSan (CPU-only) in build-fuzz/, then runs each for
# SECONDS (default 600), two at a time (nice 10), from a working corpus out/fuzz/TARGET/ that
# starts as a copy of the seeds fuzz/corpus/TARGET/ and keeps what each run adds. A crash,
# sanitizer report, leak, timeout (10 s) or RSS over 2 GiB is written to
# out/fuzz/crashes/TARGET/; the log of a run is out/fuzz/logs/TARGET.log. Prints one line per
# target: executions, coverage (edges), corpus size (inputs libFuzzer keeps), findings; exits
# 1 if a run found any. TARGET may also be a list: nifti,cli.
# A finding that is fixed goes into fuzz/corpus/TARGET/, which the test suite replays.
set -euo pipefail
cd "$(dirname "$0")/.."
all=(ply xyz obj stl pcd las raw nrrd metaimage nifti cli)
target=${1:-all}
seconds=${2:-600}
if [[ $target == all ]]; then
  targets=("${all[@]}")
else
  IFS=, read -ra targets <<<"$target"
  for t in "${targets[@]}"; do
    [[ " ${all[*]} " == *" $t "* ]] && continue
    echo "usage: scripts/fuzz.sh [all|$(IFS='|'; echo "${all[*]}")] [SECONDS]   (TARGET may be a list: nifti,cli)" >&2
    exit 2
  done
fi
[[ $seconds =~ ^[1-9][0-9]*$ ]] || { echo "scripts/fuzz.sh: SECONDS must be a positive integer" >&2; exit 2; }

# clang's libFuzzer and sanitizer runtimes (libclang-rt-dev) and its OpenMP (libomp-dev).
./scripts/install-deps.sh
for p in clang libclang-rt-dev libomp-dev; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" && continue
  sudo=""
  [[ $(id -u) -eq 0 ]] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq clang libclang-rt-dev libomp-dev >/dev/null
  break
done

CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPSS_ENABLE_CUDA=OFF \
  -DPSS_BUILD_TESTS=OFF -DPSS_BUILD_BENCH=OFF -DPSS_LIBFUZZER=ON \
  -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined" \
  >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target "${targets[@]/#/fuzz_}"

# The longest input each target is given: room for the seeds (each under 64 KiB), and for a
# command line of a few dozen arguments.
declare -A max_len=([ply]=65536 [xyz]=16384 [obj]=16384 [stl]=65536 [pcd]=65536 [las]=65536 [raw]=65536 [nrrd]=65536 [metaimage]=65536 [nifti]=65536 [cli]=2048)
export ASAN_OPTIONS=abort_on_error=0:detect_leaks=1:strict_string_checks=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
mkdir -p out/fuzz/logs

run() {
  local t=$1
  mkdir -p "out/fuzz/$t" "out/fuzz/crashes/$t"
  cp -n fuzz/corpus/"$t"/* "out/fuzz/$t/"
  local dict=()
  [[ -f fuzz/$t.dict ]] && dict=(-dict="fuzz/$t.dict")
  nice -n 10 "build-fuzz/fuzz/fuzz_$t" "out/fuzz/$t" "${dict[@]}" -max_total_time="$seconds" \
    -max_len="${max_len[$t]}" -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 \
    -artifact_prefix="out/fuzz/crashes/$t/" >"out/fuzz/logs/$t.log" 2>&1 || true
}

# Two at a time: one per core of a 2-core machine.
stamp=$(mktemp)
trap 'rm -f "$stamp"' EXIT
running=0
for t in "${targets[@]}"; do
  if ((running == 2)); then wait -n; running=$((running - 1)); fi
  echo "fuzzing $t for $seconds s"
  run "$t" &
  running=$((running + 1))
done
wait

found=0
printf '%-10s %12s %10s %8s %8s  %s\n' target execs exec/s edges corpus findings
for t in "${targets[@]}"; do
  log=out/fuzz/logs/$t.log
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | tail -1 | grep -o '[0-9]*$' || true)
  rate=$(grep -o 'stat::average_exec_per_sec: *[0-9]*' "$log" | tail -1 | grep -o '[0-9]*$' || true)
  edges=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*$' || true)
  corpus=$(grep -o 'corp: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*$' || true)
  crashes=$(find "out/fuzz/crashes/$t" -type f -newer "$stamp" | wc -l)
  ((crashes == 0)) || found=1
  printf '%-10s %12s %10s %8s %8s  %s\n' "$t" "${execs:-?}" "${rate:-?}" "${edges:-?}" "${corpus:-?}" \
    "$( ((crashes == 0)) && echo none || echo "$crashes in out/fuzz/crashes/$t/ (log: $log)")"
done
exit $found
