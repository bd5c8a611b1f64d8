#!/usr/bin/env bash
# The main job on the shipped data: installs, builds, then projects, ray traces and meshes
# the bunny's PSS, prints the tooth CT's histogram and suggested iso-values, extracts and
# renders the PSS of the bucky, fuel, tooth and engine volumes, and meshes the tooth's.
# Outputs go to out/ (images to look at: out/*.png).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
./scripts/build.sh
mkdir -p out
pss=./build/pss
set -x
$pss info data/bun_zipper.ply
$pss project data/bun_zipper.ply -o out/bunny-projected.ply --stats out/bunny-projected.json
$pss render data/bun_zipper.ply -o out/bunny.png --iterations 2 --shadows --reflections --stats out/bunny.json
$pss mesh data/bun_zipper.ply -o out/bunny-mesh.ply --stats out/bunny-mesh.json
$pss volume data/bucky_32x32x32_uint8.raw --dims 32x32x32 --type uint8 --iso 100 --view 30,20 \
  -o out/bucky.png --stats out/bucky.json
$pss volume data/fuel_64x64x64_uint8.raw --dims 64x64x64 --type uint8 --iso 30 --view 30,20 -o out/fuel.png
$pss info data/tooth_103x94x161_uint8.raw --dims 103x94x161 --type uint8
$pss volume data/tooth_103x94x161_uint8.raw --dims 103x94x161 --type uint8 --iso 125 --view 90,60 \
  -o out/tooth.png --stats out/tooth.json
$pss volume data/engine_256x256x128_uint8.nrrd --iso 75 --view 30,30 -o out/engine.png --stats out/engine.json
$pss mesh data/tooth_103x94x161_uint8.raw --dims 103x94x161 --type uint8 --iso 125 -o out/tooth-mesh.ply \
  --stats out/tooth-mesh.json
$pss extract data/bucky_32x32x32_uint8.raw --dims 32x32x32 --type uint8 --iso 100 --h 1.25 -o out/bucky-surface.ply
$pss render out/bucky-surface.ply -o out/bucky-surface.png --view 30,20
{ set +x; } 2>/dev/null
echo "outputs in $(pwd)/out:"
ls -1 out
