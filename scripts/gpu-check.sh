#!/usr/bin/env bash
# The whole check on a GPU machine that has nvcc, CMake and ninja but none of our Debian
# packages and no archive to fetch them from. On a machine with Debian 12's archive, first:
#   mkdir -p .debs && (cd .debs && apt-get download $(scripts/gpu-check.sh --packages))
# then carry .debs/ to the GPU machine and run there:
#   scripts/gpu-check.sh [DEBS_DIR=.debs] [OUT_DIR=out/gpu-check]
# It unpacks the packages into a prefix (dpkg -x: nothing is installed), builds against it
# in build-gpu/, runs the whole suite (the GPU tests compare CUDA with the CPU), runs
# compute-sanitizer on the GPU tests, and runs the benchmarks on both backends. Logs and
# JSON go to OUT_DIR; the last lines printed are the summary. Exits non-zero if a stage failed.
set -uo pipefail
cd "$(dirname "$0")/.."

# What install-deps.sh installs, less the compilers and build tools, plus the libraries
# those packages need at run time (their Depends, which a prefix does not resolve; zlib's
# runtime is on every system, and a second one on the library path would shadow it).
packages=(libglm-dev libcli11-dev libstb-dev libstb0 nlohmann-json3-dev libnanoflann-dev
          zlib1g-dev libnifti2-dev libnifti2-2 libniftiio-dev libniftiio2 libznz-dev libznz3
          libnifticdf-dev libnifticdf2 libgtest-dev libgmock-dev googletest
          libopenexr-dev libopenexr-3-1-30 libimath-dev libimath-3-1-29)
if [[ ${1:-} == --packages ]]; then
  echo "${packages[@]}"
  exit 0
fi

debs=${1:-.debs}
out=${2:-out/gpu-check}
prefix=${PSS_PREFIX:-$PWD/build-gpu/prefix}
mkdir -p "$out" "$prefix"
out=$(cd "$out" && pwd)
failed=()
summary=()
log() { printf '[gpu-check %(%T)T] %s\n' -1 "$*"; }
# stage NAME COMMAND...: runs one stage, its output in OUT_DIR/NAME.log, and records the outcome.
# Each stage is stopped after PSS_GPU_CHECK_STAGE_SECONDS (default 900).
stage() {
  local name=$1 start=$SECONDS
  shift
  log "$name: $*"
  local limit=(timeout "${PSS_GPU_CHECK_STAGE_SECONDS:-900}")
  [[ $(type -t "$1") != function ]] || limit=()  # the functions below limit their own commands
  if "${limit[@]}" "$@" >"$out/$name.log" 2>&1; then
    summary+=("ok     $name ($((SECONDS - start)) s)")
  else
    failed+=("$name")
    summary+=("FAILED $name ($((SECONDS - start)) s): see $name.log")
    tail -n 30 "$out/$name.log"
  fi
}

# 1. The packages, unpacked into the prefix: nothing is installed, nothing outside
#    build-gpu/ changes, and the programs built find the prefix's libraries on the library
#    path (the build tree's RUNPATH alone misses their own dependencies: libniftiio needs libznz).
unpack() {
  local deb missing=()
  for p in "${packages[@]}"; do
    compgen -G "$debs/${p}_*.deb" >/dev/null || missing+=("$p")
  done
  ((${#missing[@]} == 0)) || { echo "missing in $debs: ${missing[*]}"; return 1; }
  for deb in "$debs"/*.deb; do
    if command -v dpkg-deb >/dev/null; then
      dpkg-deb -x "$deb" "$prefix" || return 1
    else  # a .deb is an ar archive holding data.tar.*
      (cd "$prefix" && ar p "$OLDPWD/$deb" "$(ar t "$OLDPWD/$deb" | grep '^data.tar')" | tar -xa) || return 1
    fi
    echo "unpacked $deb"
  done
}
stage unpack unpack
export LD_LIBRARY_PATH="$prefix/usr/lib/x86_64-linux-gnu${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"

# 2. Build for this machine's GPU only (the default builds three architectures).
arch=$(nvidia-smi --query-gpu=compute_cap --format=csv,noheader 2>/dev/null | head -n1 | tr -d ' .')
nvidia-smi --query-gpu=name,driver_version,memory.total,compute_cap --format=csv >"$out/device.txt" 2>&1
nvcc --version >>"$out/device.txt" 2>&1
stage configure cmake -S . -B build-gpu -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$prefix/usr" \
  -DCMAKE_CUDA_ARCHITECTURES="${arch:-90}"
stage build cmake --build build-gpu -j"$(nproc)"
grep -q "CUDA backend ON" "$out/configure.log" || { failed+=(cuda); summary+=("FAILED the CUDA backend was not configured"); }

# 3. The whole suite; the GPU tests compare CUDA with the CPU on the same inputs.
stage tests ctest --test-dir build-gpu --output-on-failure -j"$(nproc)"
stage gpu-tests-verbose build-gpu/tests/pss_gpu_tests

# 4. compute-sanitizer on every GPU test: out-of-bounds and misaligned accesses, then reads of
#    device memory nothing wrote.
for tool in memcheck initcheck; do
  stage "sanitizer-$tool" compute-sanitizer --tool "$tool" --error-exitcode 1 build-gpu/tests/pss_gpu_tests
done

# 5. Images to look at, from both backends.
images() {
  local pss=(timeout "${PSS_GPU_CHECK_STAGE_SECONDS:-900}" build-gpu/pss) b
  for b in cuda cpu; do
    "${pss[@]}" render data/bun_zipper.ply -o "$out/bunny-$b.png" --iterations 2 --shadows --reflections --backend $b \
      --stats "$out/bunny-$b.json" || return 1
    "${pss[@]}" volume data/engine_256x256x128_uint8.nrrd --iso 75 --view 30,30 -o "$out/engine-$b.png" --backend $b \
      --stats "$out/engine-$b.json" || return 1
  done
}
stage images images

# 6. Benchmarks, both backends of the same build side by side (PSS_GPU_CHECK_BENCH=0 skips them).
[[ ${PSS_GPU_CHECK_BENCH:-1} == 0 ]] || {
stage bench-tables-cuda build-gpu/bench/bench_paper_tables --backend cuda --runs 3 --frames 10 --json "$out/paper_tables_cuda.json"
stage bench-tables-cpu build-gpu/bench/bench_paper_tables --backend cpu --runs "${PSS_GPU_CHECK_CPU_RUNS:-3}" --json "$out/paper_tables_cpu.json"
# The point kernels walking the grid again at each pass against the default that keeps the
# neighbours' indices (include/pss/points/neighbourhood.hpp): Table 2 side by side
# (PSS_GPU_CHECK_VARIANT=0 skips it).
variant() {
  cmake -S . -B build-gpu-walked -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$prefix/usr" \
    -DCMAKE_CUDA_ARCHITECTURES="${arch:-90}" -DPSS_BUILD_TESTS=OFF \
    "-DCMAKE_CUDA_FLAGS=-DPSS_DEVICE_NEIGHBOURS=0" >/dev/null &&
    cmake --build build-gpu-walked -j"$(nproc)" --target bench_paper_tables >/dev/null &&
    timeout "${PSS_GPU_CHECK_STAGE_SECONDS:-900}" build-gpu-walked/bench/bench_paper_tables --backend cuda --runs 3 \
      --frames 10 --only table2 --json "$out/paper_tables_cuda_walked.json"
}
[[ ${PSS_GPU_CHECK_VARIANT:-1} == 0 ]] || stage bench-tables-cuda-walked-neighbourhoods variant
stage bench-project build-gpu/bench/bench_project --runs 5 --large --json "$out/project.json"
}
for f in "$out"/bench-*.log; do
  echo "== $(basename "$f" .log)"
  grep '^|' "$f"
done

echo "== gpu-check on $(head -n2 "$out/device.txt" | tail -n1)"
printf '%s\n' "${summary[@]}"
((${#failed[@]} == 0))
