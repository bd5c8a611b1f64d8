#!/usr/bin/env bash
# The main job on the shipped data: installs, builds, then projects and renders the bunny
# and extracts the surfaces of the bucky and fuel volumes. Outputs go to out/.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
mkdir -p out
./scripts/build.sh
set -x
./build/pss info data/bun_zipper.ply
./build/pss project data/bun_zipper.ply -o out/bunny-projected.ply --stats out/bunny-projected.json
