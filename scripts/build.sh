#!/usr/bin/env bash
# Configures and builds pss (Release) in build/. The CUDA backend is built when nvcc is
# found, on the PATH or in /usr/local/cuda; without it pss is CPU-only.
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v nvcc >/dev/null && [[ -x /usr/local/cuda/bin/nvcc ]]; then
  export PATH=/usr/local/cuda/bin:$PATH
fi
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"
