#!/usr/bin/env bash
# Installs (with the optional parts: PCL for a peer benchmark, Open MPI for the ranks), builds and runs the whole test suite (GPU tests skip
# without a device), then builds it again under AddressSanitizer + UndefinedBehaviorSanitizer
# (CPU-only, build-asan/) and runs it there: any sanitizer report fails the run.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh --optional

./scripts/build.sh
# The optional targets that this machine's packages switch on are part of the default build.
built() { echo "$1 was not built, though its packages are installed" >&2; exit 1; }
[[ -x build/bench/peer_pcl_mls ]] || built "the PCL peer benchmark (bench/peer_pcl_mls)"
build/pss view --help 2>&1 | grep -q "in a window" || built "the viewer's window (pss view: GLFW, Dear ImGui)"
compgen -G "build/python/pss/_pss*.so" >/dev/null || built "the Python module (build/python/pss)"
# (a match, not `| grep -q`: grep's early exit would fail the pipe under pipefail)
[[ $(ldd build/pss) == *libmpi* ]] || built "pss's MPI ranks (mpirun -np N pss project)"
ctest --test-dir build --output-on-failure -j"$(nproc)"
# The GPU kernels' stack frames (a CUDA build's test gpu.kernel_stacks, which fails above the
# budget): the table, in the log.
if [[ -n $(ctest --test-dir build -N -R '^gpu\.kernel_stacks$' | grep 'Test *#') ]]; then
  ctest --test-dir build -R '^gpu\.kernel_stacks$' -V | grep -E '^[0-9]+: (\||[0-9]+ kernels)' | sed 's/^[0-9]*: //'
fi

# The sanitized run leaves out the heavy tests that tests/unsanitized.txt names (each 30 s to
# 16 min sanitized; with them this script outgrew CI's 90 minutes on 2 cores): the code they run
# is run sanitized by lighter tests. -O1 -g1 (line tables for the reports) compiles in half the
# time of -O2 -g.
# The Python module is left out: a sanitized extension cannot load into an uninstrumented python3.
# So are the MPI ranks: under LeakSanitizer a program that only starts and ends Open MPI 4.1
# reports leaks (Open MPI's own). The ranks' tests run in the build above; the tiles' work they
# send is the same code, sanitized here through the local farm.
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DPSS_ENABLE_CUDA=OFF -DPSS_BUILD_BENCH=OFF \
  -DPSS_BUILD_PYTHON=OFF -DPSS_ENABLE_MPI=OFF \
  -DCMAKE_CXX_FLAGS="-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined"
cmake --build build-asan -j"$(nproc)"
# The options reach the pss processes that the CLI tests start, too. abort_on_error makes a
# report in pss a signal, which a test expecting an ordinary failure exit still notices.
export ASAN_OPTIONS=halt_on_error=1:abort_on_error=1:detect_leaks=1:strict_string_checks=1
export UBSAN_OPTIONS=halt_on_error=1:abort_on_error=1:print_stacktrace=1
unsanitized=$(sed 's/#.*//' tests/unsanitized.txt | xargs)
suite=$(ctest --test-dir build-asan -N | sed -n 's/^ *Test *#[0-9]*: //p')
for name in $unsanitized; do
  grep -qxF "$name" <<<"$suite" ||
    { echo "tests/unsanitized.txt names $name, which the suite does not have" >&2; exit 1; }
done
# A test over 5 minutes sanitized fails here: make it lighter, or list it in tests/unsanitized.txt.
ctest --test-dir build-asan --output-on-failure -j"$(nproc)" --timeout 300 -E "^(${unsanitized// /|})\$"
