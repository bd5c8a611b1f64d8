#!/usr/bin/env bash
# The whole check on a GPU machine that has nvcc, CMake and ninja but none of our Debian
# packages and no archive to fetch them from. On a machine with Debian 12's archive, first:
#   mkdir -p .debs && (cd .debs && apt-get download $(scripts/gpu-check.sh --packages))
# then carry .debs/ to the GPU machine and run there:
#   scripts/gpu-check.sh [DEBS_DIR=.debs] [OUT_DIR=out/gpu-check]
# It unpacks the packages into a prefix (dpkg -x: nothing is installed), builds against it
# in build-gpu/, runs the GPU tests (CUDA against the CPU, on every shipped dataset),
# compute-sanitizer (memcheck, racecheck, initcheck) on the main jobs, renders images from
# both backends, runs the benchmarks on both, and profiles the hottest kernels with Nsight
# Compute. Logs and JSON go to OUT_DIR; the last lines printed are the summary. Exits
# non-zero if a stage failed.
#
# Where device time is short, build here instead (same CUDA, one architecture) and carry
# the build with the packages: PSS_GPU_CHECK_PREBUILT=1 skips the configure and build stages
# and runs the binaries of build-gpu/ (pss, tests/pss_gpu_tests, bench/*):
#   cmake -S . -B build-gpu -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CUDA_ARCHITECTURES=90 \
#     -DPSS_BUILD_VIEWER=OFF -DPSS_BUILD_PYTHON=OFF -DPSS_BUILD_FUZZ=OFF
#   ninja -C build-gpu pss_cli pss_gpu_tests bench_paper_tables bench_project
# Other knobs: PSS_GPU_CHECK_STAGE_SECONDS (each stage's limit, default 900),
# PSS_GPU_CHECK_BENCH (the benchmarks: "tables project mesh", or fewer), PSS_GPU_CHECK_PROJECT_RUNS
# (runs of each projection, default 5), PSS_GPU_CHECK_MESH_POINTS (the meshed tori's sizes,
# default "1000000 10000000"), PSS_GPU_CHECK_MESH_CPU_SECONDS (the CPU's limit for each),
# PSS_GPU_CHECK_PROFILE=0 (no ncu),
# PSS_GPU_CHECK_SANITIZERS (the compute-sanitizer tools to run, default "memcheck racecheck
# initcheck"; "" for none), PSS_GPU_CHECK_ARCHIVE=FILE (OUT_DIR packed into FILE after each
# stage, so that a run cut short still leaves its results).
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
build=build-gpu
prefix=${PSS_PREFIX:-$PWD/$build/prefix}
prebuilt=${PSS_GPU_CHECK_PREBUILT:-0}
mkdir -p "$out" "$prefix"
out=$(cd "$out" && pwd)
failed=()
summary=()
log() { printf '[gpu-check %(%T)T] %s\n' -1 "$*"; }
archive() {
  [[ -z ${PSS_GPU_CHECK_ARCHIVE:-} ]] || tar -czf "$PSS_GPU_CHECK_ARCHIVE" -C "$(dirname "$out")" "$(basename "$out")"
}
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
  archive
}
limited() { timeout "${PSS_GPU_CHECK_STAGE_SECONDS:-900}" "$@"; }

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
nvidia-smi --query-gpu=name,driver_version,memory.total,compute_cap,clocks.max.sm --format=csv >"$out/device.txt" 2>&1
nvcc --version >>"$out/device.txt" 2>&1
if [[ $prebuilt == 1 ]]; then
  summary+=("ok     prebuilt $build/ (configure and build skipped)")
else
  stage configure cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$prefix/usr" \
    -DCMAKE_CUDA_ARCHITECTURES="${arch:-90}"
  stage build cmake --build "$build" -j"$(nproc)"
  grep -q "CUDA backend ON" "$out/configure.log" || { failed+=(cuda); summary+=("FAILED the CUDA backend was not configured"); }
  # 3a. The whole suite (the CPU tests too).
  stage tests ctest --test-dir "$build" --output-on-failure -j"$(nproc)"
fi
pss=(limited "$build/pss")

# 3. The GPU tests: CUDA against the CPU on synthetic shapes with exact truth and on every
#    shipped dataset (each case prints its figures); none may skip, nor any shared cloud be
#    missing where ../shared/data is there.
gpu_tests() {
  [[ ! -d ../shared/data/clouds ]] || export PSS_REQUIRE_SHARED_DATA=1
  limited "$build/tests/pss_gpu_tests" || return 1
  ! grep -q '\[  SKIPPED \]' "$out/gpu-tests.log"
}
stage gpu-tests gpu_tests

# 4. Images to look at, from both backends, with their stats.
images() {
  local b
  for b in cuda cpu; do
    "${pss[@]}" render data/bun_zipper.ply -o "$out/bunny-$b.png" --iterations 2 --shadows --reflections --backend $b \
      --stats "$out/bunny-$b.json" || return 1
    "${pss[@]}" volume data/engine_256x256x128_uint8.nrrd --iso 75 --view 30,30 -o "$out/engine-$b.png" --backend $b \
      --stats "$out/engine-$b.json" || return 1
  done
}
stage images images

# 5. Nsight Compute on the hottest kernels, one launch each after two warm frames: speed of
#    light (against the memory's bandwidth), occupancy, registers, local-memory traffic.
profile() {
  # The kernels are one template (for_each_index) instantiated per kernel struct: match the
  # demangled name.
  local ncu=(ncu --clock-control none --kernel-name-base demangled --launch-count 1 --section SpeedOfLight
             --section Occupancy --section LaunchStats --section MemoryWorkloadAnalysis --section WarpStateStats)
  limited "${ncu[@]}" --launch-skip 2 -k regex:PrimaryRays "$build/pss" render data/bun_zipper.ply -o "$out/ncu.png" --size 512x512 \
    --reflections --frames 3 --backend cuda || return 1
  limited "${ncu[@]}" --launch-skip 2 -k regex:SecondaryRays "$build/pss" render data/bun_zipper.ply -o "$out/ncu.png" --size 512x512 \
    --reflections --frames 3 --backend cuda || return 1
  limited "${ncu[@]}" --launch-skip 2 -k regex:PrimaryRays "$build/pss" volume data/engine_256x256x128_uint8.nrrd --iso 90 \
    --size 512x512 --frames 3 -o "$out/ncu.png" --backend cuda || return 1
  limited "${ncu[@]}" -k regex:ProjectPoints "$build/pss" project data/bun_zipper.ply \
    -o "$out/ncu.ply" --backend cuda || return 1
}
[[ ${PSS_GPU_CHECK_PROFILE:-1} == 0 ]] || stage profile profile

# 6. Benchmarks, both backends of the same build side by side (PSS_GPU_CHECK_BENCH names the
#    parts: "tables project mesh" by default, "" for none). The CPU runs one frame per run: a rough
#    guide beside the GPU's median of ten.
bench=" ${PSS_GPU_CHECK_BENCH-tables project mesh} "
if [[ $bench == *" tables "* ]]; then
  for part in table2 table1 scaling; do
    stage "bench-$part-cuda" "$build/bench/bench_paper_tables" --backend cuda --runs 3 --frames 10 --only $part \
      --json "$out/paper_${part}_cuda.json"
  done
  for part in table2 table1; do
    stage "bench-$part-cpu" "$build/bench/bench_paper_tables" --backend cpu --runs 1 --frames 1 --only $part \
      --json "$out/paper_${part}_cpu.json"
  done
fi
# pss mesh of noisy tori (bench/noisy_torus.py, noise 0.003 R), the whole process timed on
# both backends one after the other (PSS_GPU_CHECK_MESH_POINTS: the sizes; the CPU's run of
# each is stopped after PSS_GPU_CHECK_MESH_CPU_SECONDS, default the stage's limit).
mesh_bench() {
  local n b tmp
  tmp=$(mktemp -d)
  for n in ${PSS_GPU_CHECK_MESH_POINTS:-1000000 10000000}; do
    python3 -c "import sys; sys.path.insert(0, 'bench'); from noisy_torus import *
write_ply('$tmp/torus-$n.ply', torus_cloud($n, 0.003))" || return 1
    for b in cuda cpu; do
      local limit=${PSS_GPU_CHECK_STAGE_SECONDS:-900}
      [[ $b == cuda ]] || limit=${PSS_GPU_CHECK_MESH_CPU_SECONDS:-$limit}
      timeout "$limit" "$build/pss" mesh "$tmp/torus-$n.ply" -o "$tmp/torus-mesh.ply" --backend $b \
        --stats "$out/mesh-$n-$b.json" || echo "| mesh $n | $b | stopped after $limit s |"
    done
  done
  rm -rf "$tmp"
}
[[ $bench != *" mesh "* ]] || stage bench-mesh mesh_bench
[[ $bench != *" project "* ]] || stage bench-project "$build/bench/bench_project" \
  --runs "${PSS_GPU_CHECK_PROJECT_RUNS:-5}" --large --json "$out/project.json"

# 7. compute-sanitizer on the main jobs, small: out-of-bounds and misaligned accesses, shared
#    memory races, reads of device memory nothing wrote; the APSS and RIMLS surfaces and the
#    headless viewer too.
main_jobs() {
  local wrap=("$@")
  "${wrap[@]}" "$build/pss" render data/bun_zipper.ply -o "$out/sanitized.png" --size 96x96 --shadows --reflections \
    --backend cuda || return 1
  "${wrap[@]}" "$build/pss" render data/bun_zipper.ply -o "$out/sanitized.png" --size 96x96 --h 0.003 \
    --backend cuda || return 1
  "${wrap[@]}" "$build/pss" volume data/bucky_32x32x32_uint8.raw --dims 32x32x32 --type uint8 --iso 100 \
    --size 96x96 --shadows --reflections -o "$out/sanitized.png" --backend cuda || return 1
  "${wrap[@]}" "$build/pss" volume data/fuel_64x64x64_uint8.raw --dims 64x64x64 --type uint8 --gradient \
    --method predictor -o "$out/sanitized.png" --size 96x96 --backend cuda || return 1
  "${wrap[@]}" "$build/pss" extract data/bucky_32x32x32_uint8.raw --dims 32x32x32 --type uint8 --iso 100 \
    -o "$out/sanitized.ply" --backend cuda || return 1
  "${wrap[@]}" "$build/pss" project data/bun_zipper.ply -o "$out/sanitized.ply" --backend cuda || return 1
  "${wrap[@]}" "$build/pss" render data/bun_zipper.ply -o "$out/sanitized.png" --size 96x96 --surface rimls \
    --shadows --reflections --backend cuda || return 1
  "${wrap[@]}" "$build/pss" project data/bun_zipper.ply -o "$out/sanitized.ply" --surface apss --backend cuda || return 1
  "${wrap[@]}" "$build/pss" mesh data/bun_zipper.ply -o "$out/sanitized.ply" --backend cuda || return 1
  "${wrap[@]}" "$build/pss" mesh data/bun_zipper.ply -o "$out/sanitized.ply" --surface rimls --backend cuda || return 1
  "${wrap[@]}" "$build/pss" mesh data/bucky_32x32x32_uint8.raw --dims 32x32x32 --type uint8 --iso 100 \
    -o "$out/sanitized.ply" --backend cuda || return 1
  # The viewer, headless: reduced frames without their hits, a volume's fields kept between frames.
  printf 'wait\nview 40 10\nset shadows on\nset reflections on\nscreenshot a\nset debug on\nwait\nset iso 90\nwait\n' \
    >"$out/view-steps.txt"
  "${wrap[@]}" "$build/pss" view data/bucky_32x32x32_uint8.raw --dims 32x32x32 --type uint8 --iso 100 --headless \
    --size 96x96 --script "$out/view-steps.txt" --screenshot-dir "$out" --backend cuda || return 1
}
for tool in ${PSS_GPU_CHECK_SANITIZERS-memcheck racecheck initcheck}; do
  stage "sanitizer-$tool" main_jobs limited compute-sanitizer --tool "$tool" --error-exitcode 1
done

for f in "$out"/bench-*.log; do
  [[ -e $f ]] || continue
  echo "== $(basename "$f" .log)"
  grep -E '^\||^meshed' "$f"
done
echo "== GPU tests"
grep -E '^\S.*: [0-9]+ (hits|points)|^\[  (FAILED|PASSED|SKIPPED)' "$out/gpu-tests.log" | head -n 80

echo "== gpu-check on $(head -n2 "$out/device.txt" | tail -n1)"
printf '%s\n' "${summary[@]}"
archive
((${#failed[@]} == 0))
