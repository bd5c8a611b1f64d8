#!/usr/bin/env bash
# Configures and builds pss (Release) in build/. The CUDA backend is built when nvcc is
# found, on the PATH or in /usr/local/cuda; without it pss is CPU-only.
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v nvcc >/dev/null && [[ -x /usr/local/cuda/bin/nvcc ]]; then
  export PATH=/usr/local/cuda/bin:$PATH
fi
# The Python module is built for Debian's python3, which has python3-numpy (scripts/install-deps.sh),
# and not for another python3 earlier on the PATH (pyenv's, a virtualenv's) that may lack NumPy.
python=()
[[ -x /usr/bin/python3 ]] && python=(-DPython3_EXECUTABLE=/usr/bin/python3)
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "${python[@]}"
cmake --build build -j"$(nproc)"
