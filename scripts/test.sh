#!/usr/bin/env bash
# Installs, builds and runs the whole test suite (GPU tests skip without a device).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh

./scripts/build.sh
ctest --test-dir build --output-on-failure -j"$(nproc)"
